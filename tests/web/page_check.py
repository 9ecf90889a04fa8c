#!/usr/bin/env python3
"""The spectator page in a real browser (docs/bots-and-watchers.md, "The spectator
page"): a ball-server, two ball-bots and a ball-watch --http on loopback, on
the test's own DDS domain, and Debian's Chromium, headless, driven over the
DevTools protocol (cdp.py). Every process is started here in a group of its
own, dies with this script (PR_SET_PDEATHSIG) and is stopped at its end,
also on a failure. Checks, each with its numbers printed:

  1. the page's ball at the watcher's frame times (its --record-frames,
     whose JSON carries every double to the bit) on the same segment equals
     the watcher's own ball BIT FOR BIT (each coordinate's IEEE bits), over
     at least 100 times; the page never holds an older segment than the
     watcher;
  2. 1000 random segments (web_probe segments): the page's own evaluation
     path (each case an info and a segment message of a match of its own
     fed to the page, the ball asked of it as its frames ask: libball and
     the client library's view on WebAssembly) equals libball's native
     ball_segment_eval BIT FOR BIT, all nine doubles of each;
  3. a frame held at a known sim time, from the side camera: the ball's
     yellow pixels (those within 25 px of it) centred within 3 px of
     libball's projection (web_probe shot), every
     court line's middle white, the court between them blue;
  4. the server killed: the page says so and keeps the last ball still; a
     new server: the page picks the match up again and the ball moves; the
     watcher stopped and started again: the same, and the page reconnects;
  5. no console errors, no uncaught exception, from start to end;
  6. the events a correction voids (fed as the stream brings them): no
     marker, struck out in the log;
  7. the canvas fills the window: its size (CSS and drawing buffer) is the
     window's at 1280x800 and again after a resize to 1000x700;
  8. the court the server judges, whole: the court message lays it out on
     MatchInfo's court_x and court_z, and from the side and behind0 cameras
     points along the far baseline, the near one and both sidelines,
     projected through the page's camera, are line pixels (red above 100:
     brighter than the court and the ground; a far line is thinner than a
     pixel) that no panel covers;
  9. the page reads at a glance: libball's level name (easy, mid, advanced,
     custom) and each side's name with its players beside the score, in the
     DOM, as the info message says them;
 10. a dead ball (a point decided, the ball still moving: the segment in
     effect judged no rally on) is marked as such, with the point;
  and a page opened mid-rally draws the ball at once (within 5 s of asking,
  the browser's start of three.js included).

  page_check.py --bin DIR --domain ID --chromium PATH --probe PATH --work DIR [--page-shot PNG]

--page-shot writes a screenshot of the whole page mid-rally (docs/img/spectator.png is one).
"""
import argparse
import ctypes
import http.client
import json
import os
import re
import shutil
import signal
import struct
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cdp import Browser  # noqa: E402

LIBC = ctypes.CDLL(None)
PR_SET_PDEATHSIG = 1
procs = []


def start(args, name, work):
    """A process in a group of its own that dies with this script."""
    out = open(os.path.join(work, name + ".log"), "w")
    p = subprocess.Popen(args, stdout=out, stderr=subprocess.STDOUT, start_new_session=True,
                         preexec_fn=lambda: LIBC.prctl(PR_SET_PDEATHSIG, signal.SIGKILL))
    procs.append(p)
    return p


def stop(p, sig=signal.SIGTERM, wait=10.0):
    """Its exit status (a signal: negative)."""
    if p.poll() is None:
        try:
            os.killpg(p.pid, sig)
            p.wait(wait)
        except (ProcessLookupError, subprocess.TimeoutExpired):
            os.killpg(p.pid, signal.SIGKILL)
            p.wait()
    return p.returncode


def server(a, work, name):
    """A server of two matches: the bots play match 0, match 1 waits for players."""
    return start([a.bin + "/ball-server", "--domain", str(a.domain), "--server-id", "1", "--startup-wait", "0",
                  "--matches", "2", "--duration", "300"], name, work)


def watcher(a, name, port):
    """ball-watch --http PORT with its own ball in its record; the page's URL once it serves."""
    record = os.path.join(a.work, name + ".jsonl")
    start([a.bin + "/ball-watch", "--domain", str(a.domain), "--http", str(port), "--no-log", "--record", record,
           "--record-frames", "--fps", "30"], name, a.work)
    deadline = time.time() + 20
    while time.time() < deadline:
        m = re.search(r"the spectator page is at (\S+)", open(os.path.join(a.work, name + ".log")).read())
        if m:
            return record, m.group(1)
        time.sleep(0.1)
    return record, None


class Record:
    """The watcher's record, read as it grows: its own frames."""

    def __init__(self, path):
        self.path, self.pos, self.frames = path, 0, []

    def read(self):
        if not os.path.exists(self.path):
            return
        with open(self.path) as f:
            f.seek(self.pos)
            for line in f:
                if not line.endswith("\n"):
                    break
                self.pos += len(line.encode())
                j = json.loads(line)
                if j.get("type") == "frame" and j.get("match") == 0:
                    self.frames.append(j)


def bits(x):
    """The IEEE bits of a double, as the page writes them."""
    return "%016x" % struct.unpack("<Q", struct.pack("<d", x))[0]


HEX = "const u = new BigUint64Array(1), d = new Float64Array(u.buffer); const hex = x => { d[0] = x; return u[0].toString(16).padStart(16, '0'); };"


def agreement(b, rec, seconds, need, grace=3.0):
    """Page against watcher at the watcher's frame times; (compared, differing, seqs older, seqs newer).

    Compared by the bits of each coordinate. The page's stream trails the watcher's record by its
    transport: a frame whose segment the page has not received yet (nothing it holds is as new)
    waits, and counts as an older segment only when the page still lacks it `grace` seconds after
    the frame was read (a segment lost on the way). A frame whose segment the page holds, or a newer
    one, is compared at once."""
    compared, differing, older, newer = 0, 0, 0, 0
    waiting = []  # (frame, when read)
    deadline = time.time() + seconds
    while time.time() < deadline and compared < need:
        time.sleep(0.2)
        rec.read()
        now = time.time()
        batch = waiting + [(f, now) for f in rec.frames[::3]]
        rec.frames, waiting = [], []
        if not batch:
            continue
        ts = json.dumps([f["sim_time"] for f, _ in batch])
        # the newest segment the page holds: the one in effect at a time after all of them
        page, held = json.loads(b.evaluate(
            "(() => { %s const S = window.spectator; return JSON.stringify([%s.map(t => { const p = S.ballAt(0, t);"
            " return p && {seq: p.seq, position: p.position.map(hex)}; }), S.ballAt(0, 1e300)]); })()" % (HEX, ts)))
        newest = held["seq"] if held else None
        for (f, read), p in zip(batch, page):
            if newest is None or newest < f["segment_seq"]:
                if now - read < grace:
                    waiting.append((f, read))
                else:
                    older += 1
                continue
            if p is None:
                continue
            if p["seq"] != f["segment_seq"]:
                # a segment the watcher did not have at its frame yet (a correction): the page's is newer
                if p["seq"] > f["segment_seq"]:
                    newer += 1
                else:
                    older += 1
                continue
            differing += p["position"] != [bits(x) for x in f["position"]]
            compared += 1
    return compared, differing, older, newer


def shot_points(a, browser, work, name, held, points):
    """A screenshot of the held frame; per point, its projection and the brightest red around it (web_probe shot)."""
    shot = os.path.join(work, name + ".png")
    with open(shot, "wb") as f:
        f.write(browser.screenshot(held))
    cam = held["camera"]
    args = [a.probe, "shot", shot, repr(cam["fov"])] + [repr(x) for x in cam["eye"] + cam["target"] + cam["up"]]
    args += [repr(x) for x in held["ball"]["position"]]
    for p in points:
        args += [repr(x) for x in p]
    return subprocess.run(args, capture_output=True, text=True, check=True).stdout.splitlines()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", required=True)
    ap.add_argument("--domain", type=int, required=True)
    ap.add_argument("--chromium", required=True)
    ap.add_argument("--probe", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--page-shot")
    a = ap.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    failures = []

    def check(ok, text):
        print(("ok   " if ok else "FAIL ") + text, flush=True)
        if not ok:
            failures.append(text)

    browser = None
    try:
        srv = server(a, a.work, "server")
        for i in range(2):
            # (they miss a ball in seven: points are decided and dead balls fly, check 10)
            start([a.bin + "/ball-bot", "--domain", str(a.domain), "--player", str(i), "--seed", str(7 + i),
                   "--duration", "300", "--miss", "0.15"], "bot%d" % i, a.work)
        record, url = watcher(a, "watch", 0)
        check(url is not None and url.startswith("http://127.0.0.1:"), "ball-watch serves the page on loopback: %s" % url)
        if url is None:
            return 1
        # mid-rally: the watcher evaluates match 0's ball (a slow start, under ASan and other tests,
        # is the server's and the bots', not the page's)
        started, deadline = Record(record), time.time() + 30
        while not started.frames and time.time() < deadline:
            time.sleep(0.1)
            started.read()
        check(bool(started.frames), "the rally is under way before the page opens")
        browser = Browser(a.chromium)
        opened = time.time()
        browser.open(url)
        browser.wait_for("window.spectator && window.spectator.sample(0) && window.spectator.sample(0).ball", 30,
                         "the page's first ball")
        first = time.time() - opened
        # (three.js's start and software GL's first frame: about 2 s alone, 5 to 9 s beside other tests
        # under ASan on two cores)
        check(first <= 12.0, "opened mid-rally, the page drew the ball %.2f s after it was asked for" % first)
        listed = browser.wait_for("window.spectator.matches().length === 2 && window.spectator.matches()", 10,
                                  "both matches listed")
        check(sorted(listed) == [0, 1], "the page lists every match the watcher sees: %s" % listed)

        # 7. the canvas fills the window, and follows it
        size = ("(() => { const c = document.getElementById('court'); return [window.innerWidth, window.innerHeight,"
                " c.clientWidth, c.clientHeight, c.width, c.height]; })()")
        sizes = [browser.evaluate(size)]
        browser.send("Emulation.setDeviceMetricsOverride", width=1000, height=700, deviceScaleFactor=1, mobile=False)
        time.sleep(0.5)
        sizes.append(browser.evaluate(size))
        browser.send("Emulation.setDeviceMetricsOverride", width=1280, height=800, deviceScaleFactor=1, mobile=False)
        time.sleep(0.5)
        sizes.append(browser.evaluate(size))
        check([s_[:2] for s_ in sizes] == [[1280, 800], [1000, 700], [1280, 800]] and
              all(s_[2:4] == s_[:2] and s_[4:] == s_[:2] for s_ in sizes),
              "the canvas fills the window: window, canvas (CSS) and its drawing buffer %s at 1280x800, %s after a "
              "resize to 1000x700, %s back" % tuple("%dx%d, %dx%d, %dx%d" % tuple(s_) for s_ in sizes))

        # 9. it reads at a glance: the level by libball's name, whose side each number of the score is
        glance = browser.wait_for(
            "(() => { const m = window.spectator.message(0, 'info'); const s = document.getElementById('score'),"
            " st = document.getElementById('status'); return m && !document.getElementById('scoreboard').hidden &&"
            " {level: m.level_name, sides: m.sides, score: s.textContent, status: st.textContent}; })()", 10, "the scoreboard")
        side_words = [sd["name"] for sd in glance["sides"]] + ["player %d" % i for sd in glance["sides"] for i in sd["slots"]]
        check(glance["level"] in ("easy", "mid", "advanced", "custom") and ("level " + glance["level"]) in glance["status"]
              and all(w_ in glance["score"] for w_ in side_words) and bool(re.search(r"\d+ : \d+", glance["score"])),
              "the scoreboard says \"%s\" and \"%s\": libball's level name %s and each side's name and players %s"
              % (glance["score"], glance["status"], glance["level"], side_words))

        # 1. the page's ball and the watcher's
        rec = Record(record)
        n, differing, older, newer = agreement(browser, rec, 20, 150)
        check(n >= 100 and differing == 0 and older == 0,
              "the page's ball at %d watcher frame times, to the bit: %d differ in some bit; "
              "%d times the page held a newer segment (a correction), %d an older one" % (n, differing, newer, older))

        # 10. a dead ball: a point decided, the ball still moving, marked as such (the bots miss one ball in seven)
        waited = time.time()
        dead = browser.wait_for(
            "(() => { const s = window.spectator.sample(0), d = document.getElementById('dead');"
            " return s && s.dead && s.ball && !d.hidden && {ball: s.ball, text: d.textContent}; })()", 60,
            "a dead ball")
        check(dead["ball"]["live"] == 0 and dead["text"].startswith("dead ball: ") and "point" in dead["text"],
              "a dead ball %.1f s into the watch: the segment in effect (seq %d) judged no rally on, and the page says "
              "\"%s\"" % (time.time() - waited, dead["ball"]["seq"], dead["text"]))

        if a.page_shot:  # from behind player 0, the ball in play over the court
            browser.evaluate("document.querySelector('#cameras button[data-preset=behind0]').click()")
            time.sleep(1.0)
            browser.wait_for("(() => { const s = window.spectator.sample(0); const b = s && s.ball;"
                             " return b && b.live && b.position[1] > 0.5 && b.position[0] > 8 && b.position[0] < 16; })()",
                             30, "the ball in play over the court")
            with open(a.page_shot, "wb") as f:
                f.write(browser.screenshot({"x": 0, "y": 0, "width": 1280, "height": 800}))

        # 2. 1000 random segments: the page's own path (a match of each, fed as the stream feeds it) against
        # ball_segment_eval, by the bits
        cases = json.loads(subprocess.run([a.probe, "segments", "1000", "2026"], capture_output=True, text=True,
                                          check=True).stdout, parse_int=float)
        keys = ("position", "velocity", "spin")
        got = browser.evaluate(
            "(() => { %s const S = window.spectator, base = S.message(0, 'info'), out = [];"
            " for (const [i, c] of %s.entries()) {"
            "  const id = 1000000 + i, info = JSON.parse(JSON.stringify(base));"
            "  info.match = info.info.match = id; info.info.segment_seq = 0; info.info.sim_time = c.t;"
            "  Object.assign(info.info.model, c.model);"
            "  S.feed(info);"
            "  S.feed({type: 'segment', match: id, segment: {match: id, server: info.info.server,"
            "   term: info.info.term, seq: 1, cause: 'serve',"
            "   index: 0, t0: c.seg.t0, p0: c.seg.p0, v0: c.seg.v0, s0: c.seg.s0, grounded: c.seg.grounded, sound: false,"
            "   correction: false, server_time: 0, model_hash: 0, sample_seq: 0, sample_source_time: 0,"
            "   sample_capture_time: 0, play: info.info.play}});"
            "  const b = S.ballAt(id, c.t);"
            "  out.push(b && %s.map(k => b[k].map(hex)));"
            "  S.forget(id); }"
            " return out; })()" % (HEX, json.dumps([{"model": c["model"], "seg": c["seg"], "t": c["t"]} for c in cases]),
                                   json.dumps(keys)))
        answered = sum(g is not None for g in got)
        differing = sum(g is None or g != [[bits(x) for x in c[k]] for k in keys] for c, g in zip(cases, got))
        check(len(got) == 1000 and answered == 1000 and differing == 0,
              "1000 random segments through the page's own path (an info and a segment each, the ball asked of the "
              "page): %d answered, %d differ from libball's native ball_segment_eval in some bit of the 9000 doubles"
              % (answered, differing))

        # 3. a frame held still: the ball and the court lines where libball's projection puts them
        t = browser.wait_for(
            "(() => { const s = window.spectator.sample(0); const p = s && s.ball && s.ball.position;"
            " return p && p[1] > 0.3 && p[0] > 3 && p[0] < 21 ? s.t : null; })()", 20, "the ball over the court")
        held = browser.evaluate("window.spectator.hold(0, %r, 'side')" % t)
        time.sleep(0.3)  # a composited frame of it
        floor = held["floor"]
        points = [[0.5 * (l[0] + l[2]), floor["level"], 0.5 * (l[1] + l[3])] for l in floor["lines"]]
        c = floor["court"]
        points.append([c[0] + 0.25 * (c[2] - c[0]), floor["level"], c[1] + 0.25 * (c[3] - c[1])])
        out = shot_points(a, browser, a.work, "held", held, points)
        m = re.match(r"ball projected=(\S+),(\S+) centroid=(\S+),(\S+) pixels=(\d+) size=(\d+)x(\d+)", out[0])
        px, py, cx, cy = map(float, m.groups()[:4])
        check(int(m.group(5)) >= 4 and abs(px - cx) <= 3 and abs(py - cy) <= 3,
              "held frame (%s): the ball's %s yellow pixels centred at %.1f, %.1f, libball projects it at %.1f, %.1f"
              % (m.group(6) + "x" + m.group(7), m.group(5), cx, cy, px, py))
        reds = [int(re.search(r"max_red=(-?\d+)", x).group(1)) for x in out[1:]]
        check(all(r > 150 for r in reds[:-1]) and reds[-1] < 100,
              "held frame: the red channel at the %d court lines' middles %s (white), in a service box %d (blue)"
              % (len(reds) - 1, reds[:-1], reds[-1]))

        # 8. the court the server judges, whole, from the side and from behind player 0
        info = browser.evaluate("window.spectator.message(0, 'info').info")
        cx0, cx1 = info["court_x"]
        cz0, cz1 = info["court_z"]
        check(held["judged"] == [cx0, cz0, cx1, cz1] and floor["court"] == [cx0, cz0, cx1, cz1],
              "the court message lays the floor out on MatchInfo's court: x in [%g, %g], z in [%g, %g] m (%s)"
              % (cx0, cx1, cz0, cz1, floor["court"]))
        lw = 0.04  # half a court line: the outer lines lie inside the court
        # (the middles of the baselines left out: the players' rackets stand there)
        lines = {"far baseline": [[cx1 - lw, floor["level"], cz0 + f * (cz1 - cz0)] for f in (0.05, 0.2, 0.3, 0.7, 0.8, 0.95)],
                 "near baseline": [[cx0 + lw, floor["level"], cz0 + f * (cz1 - cz0)] for f in (0.05, 0.25, 0.75, 0.95)],
                 "sideline z0": [[cx0 + f * (cx1 - cx0), floor["level"], cz0 + lw] for f in (0.05, 0.3, 0.6, 0.95)],
                 "sideline z1": [[cx0 + f * (cx1 - cx0), floor["level"], cz1 - lw] for f in (0.05, 0.3, 0.6, 0.95)]}
        for cam in ("side", "behind0"):
            held = browser.evaluate("window.spectator.hold(0, %r, %r)" % (t, cam))
            time.sleep(0.3)
            names = [n for n in lines for _ in lines[n]]
            out = shot_points(a, browser, a.work, "court_" + cam, held, [p for n in lines for p in lines[n]])
            found = [re.search(r"point projected=(\S+),(\S+) max_red=(-?\d+)", x) for x in out[1:]]
            xy = [(float(f.group(1)), float(f.group(2))) if f else (-1.0, -1.0) for f in found]
            reds = [int(f.group(3)) if f else -1 for f in found]
            clear = browser.evaluate("%s.map(([x, y]) => document.elementFromPoint(x, y) === document.getElementById('court'))"
                                     % json.dumps(xy))
            inside = all(0 <= x < held["width"] and 0 <= y < held["height"] for x, y in xy)
            # (a line far off is thinner than a pixel: brighter than the court's blue, red 56, and the ground's, 77)
            bad = ["%s at %.0f,%.0f (red %d%s)" % (n, x, y, r, "" if c else ", under a panel")
                   for n, (x, y), r, c in zip(names, xy, reds, clear) if r <= 100 or not c]
            check(inside and not bad,
                  "from the %s camera (%dx%d): %d points on the far and near baselines and both sidelines are white "
                  "line pixels (red above 100) no panel covers (red %d to %d)%s" % (cam, held["width"], held["height"], len(xy),
                                                                   min(reds), max(reds), ": " + ", ".join(bad) if bad else ""))
        browser.evaluate("window.spectator.release()")

        # 4. the server killed, then a new one
        stop(srv, signal.SIGKILL)
        killed = time.time()
        browser.wait_for("window.spectator.sample(0).live === false", 10, "the page to see the server gone")
        gone_after = time.time() - killed
        s1 = browser.evaluate("JSON.stringify(window.spectator.sample(0))")
        time.sleep(1.0)
        s2 = browser.evaluate("JSON.stringify(window.spectator.sample(0))")
        banner = browser.evaluate("document.getElementById('banner').hidden === false && "
                                  "document.getElementById('banner').textContent")
        check(s1 == s2 and bool(banner), "server killed: the page said so after %.1f s (\"%s\") and its ball stood "
                                         "still for 1 s: %s" % (gone_after, banner, json.loads(s2)["ball"]))
        srv = server(a, a.work, "server2")
        back = time.time()
        # playing again, not only announced: a waiting match's clock stands until the bots are back
        browser.wait_for("(() => { const s = window.spectator.sample(0); "
                         "return s && s.live && s.ball && s.state === 'playing'; })()", 30,
                         "the page to pick the match up again")
        t1 = browser.evaluate("window.spectator.sample(0).t")
        time.sleep(1.0)
        t2 = browser.evaluate("window.spectator.sample(0).t")
        check(t2 > t1, "a new server: the page picked the match up after %.1f s, and its clock runs (%.2f to %.2f s)"
              % (time.time() - back - 1.0, t1, t2))
        rec.read()
        rec.frames = []
        n, differing, older, newer = agreement(browser, rec, 15, 30)
        check(n >= 30 and differing == 0 and older == 0,
              "after the new server: %d watcher frame times, %d differ in some bit" % (n, differing))

        # the watcher stopped and started again on the same port: the page says so, holds the ball, comes back
        port = int(re.match(r"http://[^:/]+:(\d+)/", url).group(1))
        watch = [p for p in procs if "ball-watch" in p.args[0]][0]
        check(stop(watch) == 0, "ball-watch stopped (SIGTERM) with status 0 while a page streamed")
        browser.wait_for("window.spectator.connected() === false", 10, "the page to see the watcher gone")
        s1 = browser.evaluate("JSON.stringify(window.spectator.sample(0))")
        time.sleep(1.0)
        s2 = browser.evaluate("JSON.stringify(window.spectator.sample(0))")
        banner = browser.evaluate("document.getElementById('banner').hidden === false && "
                                  "document.getElementById('banner').textContent")
        check(s1 == s2 and bool(banner), "watcher gone: the page said so (\"%s\") and its ball stood still" % banner)
        record, url2 = watcher(a, "watch2", port)
        back = time.time()
        browser.wait_for("(() => { const s = window.spectator.connected() && window.spectator.sample(0);"
                         " return s && s.live && s.ball; })()", 20, "the page to reconnect")
        check(url2 == url, "a watcher on the same port: the page reconnected by itself after %.1f s"
              % (time.time() - back))
        rec = Record(record)
        n, differing, older, newer = agreement(browser, rec, 15, 30)
        check(n >= 30 and differing == 0 and older == 0,
              "after the reconnection: %d watcher frame times, %d differ in some bit" % (n, differing))

        # bounded: the page's stream and 7 more are served, the 9th is told 503, the page goes on;
        # two streams from each address (its share), from other loopback addresses than the browser's
        host, port = re.match(r"http://([^:/]+):(\d+)/", url).groups()
        streams, codes = [], []
        for k in range(8):
            c = http.client.HTTPConnection(host, int(port), timeout=5, source_address=("127.0.0.%d" % (2 + k // 2), 0))
            c.request("GET", "/stream")
            r = c.getresponse()
            codes.append(r.status)
            streams.append(c)
        for c in streams:
            c.close()
        still = browser.evaluate("window.spectator.connected()")
        check(codes == [200] * 7 + [503] and still,
              "pages at once: 7 more streams served, the next told %d; the page still connected: %s" % (codes[-1], still))

        # 6. what a correction takes back (docs/protocol.md, "Corrections: hits found late"), fed as
        # the stream brings it to a match of its own, seqs across the 32-bit wrap: events before the
        # correction's t0, of its own segment or a newer one, or of a kind no correction voids, stand
        base = 2 ** 32 - 2
        events = [  # (seq, kind, time, segment_seq, arrives after the correction, void)
            (1, "racket", 1.00, base, False, False), (2, "floor", 1.30, base + 1, False, True),
            (3, "net", 1.30, base + 1, False, True), (4, "serve", 1.35, base + 1, False, False),
            (5, "point", 1.40, base + 1, False, True), (6, "floor", 1.20, base + 1, False, False),
            (7, "racket", 1.50, base + 1, True, True), (8, "racket", 1.50, 1, True, False),
            (9, "floor", 1.60, 2, True, False)]
        fake = 4242

        def event(e):
            return {"type": "event", "match": fake, "text": e[1], "event": {
                "match": fake, "server": 1, "seq": e[0], "kind": e[1], "index": -1, "side": 0, "in_play": True,
                "sound": False, "time": e[2], "server_time": 0, "point": [0, 0, 0], "velocity_in": [0, 0, 0],
                "velocity_out": [0, 0, 0], "segment_seq": e[3], "reason": "none", "score": [0, 0], "value": 0}}
        feed = [event(e) for e in events if not e[4]]
        play = browser.evaluate("window.spectator.message(0, 'info').info.play")
        feed.append({"type": "segment", "match": fake, "segment": {
            "match": fake, "server": 1, "seq": 1, "t0": 1.2, "p0": [0, 1, 0], "v0": [1, 0, 0], "s0": [0, 0, 0],
            "grounded": False, "cause": "racket", "index": 0, "sound": True, "correction": True, "server_time": 0,
            "model_hash": 0, "sample_seq": 0, "sample_source_time": 0, "sample_capture_time": 0, "play": play}})
        feed += [event(e) for e in events if e[4]]
        for msg in feed:
            browser.evaluate("window.spectator.feed(%s)" % json.dumps(msg))
        held = browser.evaluate("window.spectator.events(%d)" % fake)
        want = [{"seq": e[0], "void": e[5]} for e in events]
        got = sorted(held or [], key=lambda x: x["seq"])
        check(got == want, "a correction voids %d of %d events, those after its t0 written before it, whichever "
              "came first: %s" % (sum(x["void"] for x in got), len(got), [x["seq"] for x in got if x["void"]]))

        # 5. no console errors
        errors = browser.console + [("error", e) for e in browser.evaluate("window.spectator.errors")]
        check(not errors, "no console errors or exceptions: %s" % (errors or "none"))
    except Exception as e:  # a failure of the test itself is a failure
        check(False, "%s: %s" % (type(e).__name__, e))
    finally:
        if browser:
            browser.close()
        ends = [(p.args[0].split("/")[-1], p.returncode if p.returncode == -signal.SIGKILL else stop(p)) for p in procs]
    # every program ends well when asked to (the server killed on purpose aside)
    check(all(rc in (0, -signal.SIGKILL) for _, rc in ends) and sum(rc == -signal.SIGKILL for _, rc in ends) <= 1,
          "every program ended with status 0 when stopped: %s" % ", ".join("%s %d" % e for e in ends))
    print("page_check: %s" % ("FAILED: %d checks" % len(failures) if failures else "passed"), flush=True)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
