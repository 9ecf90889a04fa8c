#!/usr/bin/env python3
"""libball and the page's core on WebAssembly in a real browser
(cmake/BallWasm.cmake, server/web/wasm/page_core.cpp,
server/web/page/ballwasm.js): the module and the glue served by Python's
http.server on 127.0.0.1 (a free port, a thread of this script; Chromium
refuses to fetch a .wasm from a file:// page), opened in Debian's Chromium,
headless, driven over the DevTools protocol (cdp.py). Chromium is the one
process left running (web_probe is run to its end first): in a group of its
own, it dies with this script (PR_SET_PDEATHSIG, by setpriv) and is stopped
at its end, also on a failure.
Checks, each with its numbers printed:

  1. the module loads; it imports nothing the glue must stub, or only WASI
     functions, and none of them is called;
  2. the glue's layout of ball_model, ball_segment, ball_state, ball_field,
     ball_plane and ball_racket_def is the compiler's (page_core_layout);
  3. the page's core (the client library's MatchView over libc++'s
     containers, the glue's copies by the module's paths): MATCHES matches
     opened, each given an info and 40 segments (seq s starting at t0 = s
     s, flying 1 m/s along x without drag), each answers the ball at
     t = 40.5 s on seq 40 at x = 0.5 m exactly and keeps its window of 16
     (the ball at 20.5 s is none: seq 20 is gone); the module's memory
     grows on the way, and all of it is forgotten;
  4. COUNT random segments of each SEED (web_probe segments COUNT SEED): the
     glue's segmentEval, that is ball_segment_eval in the module, equals the
     native ball_segment_eval BIT FOR BIT, each of the nine doubles compared
     by its IEEE bits (so -0 is not +0): the count compared and the
     mismatches;
  5. no console errors, no uncaught exception.

Bit for bit holds for any seed: the arithmetic is IEEE doubles without
contraction on both sides (BALL_C_FLOAT, cmake/BallFloat.cmake), and libball
computes exp, expm1, log and log1p itself (libball/src/elementary.c), so
neither wasi-libc's libm nor glibc's is in the numbers (docs/benchmarks.md,
"WebAssembly toolchain").

  wasm_check.py --chromium PATH --probe PATH --wasm FILE --glue FILE --work DIR [--count N] [--seed S]...
"""
import argparse
import functools
import http.server
import json
import os
import shlex
import shutil
import struct
import subprocess
import sys
import tempfile
import threading

sys.dont_write_bytecode = True  # no __pycache__ of cdp.py in the source tree
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cdp import Browser  # noqa: E402

# A MatchInfo message as ball-watch --http writes it (spectator.cpp,
# info_message; records.cpp's keys): match MATCH, playing, no drag
def info_message(match):
    play = {"score": [0, 0], "serving_side": 0, "rally": 0, "live": True, "striker": 0, "bounces": 0,
            "bounce_side": 0, "net": False, "rally_start": 0.0, "serve_due": False, "serve_at": 0.0, "event_seq": 0}
    slot = {"held": False, "present": False, "samples": 0, "last_seq": 0, "last_capture_time": 0.0,
            "owner": "000000000000000000000000"}
    info = {"match": match, "server": 1, "server_time": 1000.0, "revision": 1, "state": "playing", "scene": "tennis",
            "level": 1, "players": 2, "play": play, "pause_reason": "none", "pause_slot": -1, "segment_seq": 0,
            "frame_time": 1 / 60, "time_base": 1.0, "sim_time": 1.0, "state_rate": 60.0, "player_timeout": 1.0,
            "max_sample_age": 2.0, "max_sample_lead": 0.5, "model_hash": 0, "net_x": 11.885, "court_x": [0, 23.77],
            "court_z": [0, 10.97], "serve_delay": 1.5, "max_rally_time": 60.0, "serve_v_up": 4.0, "seed": 1,
            "segment_cause": "serve", "segment_index": -1, "segment_t0": 0.0, "segment_p0": [0, 1, 0],
            "segment_v0": [0, 0, 0], "segment_s0": [0, 0, 0], "max_racket_speed": 50.0, "racket_margin": 8.0,
            "segment_grounded": False, "slots": [slot] * 4,
            "model": {"gravity": 9.81, "mass": 0.057, "air_friction": 0.0, "spin_damping": 1.0, "radius": 0.0,
                      "floor_level": 0.0, "effects": 0, "extrapolation_time": 0.25, "stale_time": 1.0}}
    return {"type": "info", "match": match, "live": True, "real": 1000.0, "model_hash": "0000000000000000",
            "level_name": "easy", "sides": [], "info": info}


def segment_message(match, seq):
    return {"type": "segment", "match": match, "segment": {
        "match": match, "server": 1, "seq": seq, "cause": "floor", "index": -1, "t0": float(seq),
        "p0": [0, 1, 0], "v0": [1, 0, 0], "s0": [0, 0, 0], "grounded": True, "sound": False, "correction": False,
        "server_time": 1000.0, "model_hash": 0, "sample_seq": 0, "sample_source_time": 0, "sample_capture_time": 0,
        "play": info_message(match)["info"]["play"]}}


PAGE = '<!doctype html>\n<meta charset="utf-8">\n<title>ball.wasm</title>\n<link rel="icon" href="data:,">\n<script src="ballwasm.js"></script>\n'
KEYS = ("position", "velocity", "spin")
BATCH = 5000  # segments per evaluation over the DevTools protocol


def bits(x):
    """The IEEE bits of a double, as the page writes them."""
    return "%016x" % struct.unpack("<Q", struct.pack("<d", x))[0]


def ulps(a, b):
    """How many doubles apart two of the same sign are (-1: of other signs)."""
    x, y = int(a, 16), int(b, 16)
    return abs(x - y) if (x >> 63) == (y >> 63) else -1


class Quiet(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args):
        pass


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--chromium", required=True)
    ap.add_argument("--probe", required=True)
    ap.add_argument("--wasm", required=True)
    ap.add_argument("--glue", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--count", type=int, default=1000, help="segments of each seed")
    ap.add_argument("--seed", type=int, action="append", help="again for more seeds (default 2026)")
    a = ap.parse_args()
    seeds = a.seed or [2026]
    shutil.rmtree(a.work, ignore_errors=True)
    www = os.path.join(a.work, "www")
    os.makedirs(www)
    failures = []

    def check(ok, text):
        print(("ok   " if ok else "FAIL ") + text, flush=True)
        if not ok:
            failures.append(text)

    # what is served: the glue and the module as the page will have them, a page, the cases
    shutil.copy(a.glue, os.path.join(www, "ballwasm.js"))
    shutil.copy(a.wasm, os.path.join(www, "ball.wasm"))
    with open(os.path.join(www, "index.html"), "w") as f:
        f.write(PAGE)
    # each seed's JSON array as web_probe printed it (the doubles' text untouched), joined into one
    texts = [subprocess.run([a.probe, "segments", str(a.count), str(seed)], capture_output=True, text=True,
                            check=True).stdout.strip() for seed in seeds]
    cases_text = "[" + ",".join(t[1:-1] for t in texts if t[1:-1].strip()) + "]\n"
    with open(os.path.join(www, "cases.json"), "w") as f:
        f.write(cases_text)
    cases = json.loads(cases_text, parse_int=float)  # "-0" is -0.0, not the int 0
    names = ["seed %d case %d" % (seed, i) for seed in seeds for i in range(a.count)]
    # Browser runs the path it is given: this one sets PR_SET_PDEATHSIG and execs chromium (and
    # Debian's /usr/bin/chromium execs the browser), so the browser dies with this script
    chromium = os.path.join(a.work, "chromium")
    with open(chromium, "w") as f:
        f.write('#!/bin/sh\nexec setpriv --pdeathsig KILL -- %s "$@"\n' % shlex.quote(a.chromium))
    os.chmod(chromium, 0o755)

    tempfile.tempdir = a.work  # Browser's profile folder: here, not left in /tmp by a killed run
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), functools.partial(Quiet, directory=www))
    threading.Thread(target=server.serve_forever, daemon=True).start()
    url = "http://127.0.0.1:%d/" % server.server_address[1]
    browser = None
    try:
        browser = Browser(chromium)
        browser.open(url)
        browser.wait_for("window.BallWasm", 20, "the glue to load")
        # 1. the module, and what it imports
        got = browser.evaluate(
            "BallWasm.load('ball.wasm').then(b => { window.ball = b; return {imports: b.imports,"
            " bytes: b.exports.memory.buffer.byteLength}; })")
        size = os.path.getsize(a.wasm)
        check(got is not None and all(i.startswith("wasi_snapshot_preview1.") for i in got["imports"]),
              "%s (%d bytes) loaded from %s with WebAssembly.instantiate; it imports %s"
              % (os.path.basename(a.wasm), size, url, ", ".join(got["imports"]) or "nothing"))

        # 2. the glue's layout against the compiler's, in page_core.cpp's order
        glue = browser.evaluate(
            "(() => { const L = BallWasm.layout, s = L.segment, st = L.state, f = L.field;"
            " return [L.model, s.size, s.t0, s.p0, s.v0, s.s0, s.grounded, st.size, st.position, st.velocity,"
            " st.spin, f.size, f.name, f.type, f.offset, L.vec3, L.plane, L.racket]; })()")
        compiled = browser.evaluate("Array.from({length: %d}, (_, i) => ball.exports.page_core_layout(i))" % len(glue))
        end = browser.evaluate("ball.exports.page_core_layout(%d)" % len(glue))
        check(glue == compiled and end == -1, "ballwasm.js's %d sizes and offsets are wasm32's: %s" % (len(glue), glue))

        # 3. the page's core: MatchView over libc++'s containers, fed through the glue; the memory grows under it
        matches = 2000
        core = browser.evaluate(
            "(() => { const p = ball.pageCore(), info = %s, seg = %s, n = %d, out = {ok: 0, info: 0, segs: 0};"
            " for (let m = 0; m < n; ++m) {"
            "  info.match = info.info.match = seg.match = seg.segment.match = m;"
            "  out.info += p.take(info, 0);"
            "  for (let s = 1; s <= 40; ++s) { seg.segment.seq = s; seg.segment.t0 = s; out.segs += p.take(seg, 0) === 0; }"
            "  const b = p.ball(m, 40.5), gone = p.ball(m, 20.5);"
            "  out.ok += b !== null && b.seq === 40 && b.position[0] === 0.5 && gone === null; }"
            " out.bytes = ball.exports.memory.buffer.byteLength;"
            " for (let m = 0; m < n; ++m) p.forget(m);"
            " out.after = p.ball(0, 40.5); p.close(); return out; })()"
            % (json.dumps(info_message(0)), json.dumps(segment_message(0, 1)), matches))
        check(core["info"] == matches and core["segs"] == 40 * matches and core["ok"] == matches
              and core["after"] is None and core["bytes"] > got["bytes"],
              "page core: %d matches, %d infos and %d segments taken; %d answer seq 40 at x = 0.5 m and keep 16 "
              "segments; memory %d -> %d bytes; forgotten: %s"
              % (matches, core["info"], core["segs"], core["ok"], got["bytes"], core["bytes"], core["after"]))

        # 4. the cases, fetched by the page, evaluated by the module; each double's bits back
        browser.evaluate("fetch('cases.json').then(r => r.json()).then(c => { window.cases = c; return c.length; })")
        compared, mismatches, segments, worst, signs, shown = 0, 0, 0, 0, 0, []
        for first in range(0, len(cases), BATCH):
            got = browser.evaluate(
                "(() => { const u = new BigUint64Array(1), d = new Float64Array(u.buffer);"
                " const hex = x => { d[0] = x; return u[0].toString(16).padStart(16, '0'); };"
                " return cases.slice(%d, %d).map(c => { const r = ball.segmentEval(c.model, c.seg, c.t);"
                " return %s.map(k => r[k].map(hex)); }); })()" % (first, first + BATCH, json.dumps(KEYS)))
            for i, (c, r) in enumerate(zip(cases[first:first + BATCH], got)):
                before = mismatches
                for k, key in enumerate(KEYS):
                    for j in range(3):
                        want, have = bits(c[key][j]), r[k][j]
                        compared += 1
                        if want != have:
                            mismatches += 1
                            apart = ulps(want, have)
                            signs += apart < 0
                            worst = max(worst, apart)
                            if len(shown) < 5:
                                shown.append("%s %s[%d]: native %s, wasm %s" % (names[first + i], key, j, want, have))
                segments += mismatches > before
        for s in shown:
            print("     " + s)
        check(len(cases) == a.count * len(seeds) and compared == 9 * len(cases) and mismatches == 0,
              "%d segments of seeds %s, %d doubles compared by their bits: %d mismatches, in %d segments (%d of "
              "sign, the largest other %d ulp)" % (len(cases), ", ".join(map(str, seeds)), compared, mismatches,
                                                   segments, signs, worst))

        stubs = browser.evaluate("ball.stubCalls")
        check(not stubs, "WASI stubs called: %s" % (stubs or "none"))
        # 5. a quiet page
        check(not browser.console, "no console errors or exceptions: %s" % (browser.console or "none"))
    except Exception as e:  # a failure of the test itself is a failure
        check(False, "%s: %s" % (type(e).__name__, e))
    finally:
        if browser:
            browser.close()
        server.shutdown()
        server.server_close()
    print("wasm_check: %s" % ("FAILED: %d checks" % len(failures) if failures else "passed"), flush=True)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
