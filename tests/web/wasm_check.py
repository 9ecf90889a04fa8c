#!/usr/bin/env python3
"""libball on WebAssembly in a real browser (cmake/BallWasm.cmake,
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
  2. the glue's layout of ball_model, ball_segment, ball_state and
     ball_field is the compiler's (wasm_probe_layout);
  3. the C++17 probe (std::map, std::vector, std::deque over libball's C
     API; tests/web/wasm_probe.cpp) gives its known answer, 64 n - 2080, and
     grows the module's memory on the way;
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

        # 2. the glue's layout against the compiler's, in wasm_probe.cpp's order
        glue = browser.evaluate(
            "(() => { const L = BallWasm.layout, s = L.segment, st = L.state, f = L.field;"
            " return [L.model, s.size, s.t0, s.p0, s.v0, s.s0, s.grounded, st.size, st.position, st.velocity,"
            " st.spin, f.size, f.name, f.type, f.offset, L.vec3]; })()")
        compiled = browser.evaluate("Array.from({length: %d}, (_, i) => ball.exports.wasm_probe_layout(i))" % len(glue))
        end = browser.evaluate("ball.exports.wasm_probe_layout(%d)" % len(glue))
        check(glue == compiled and end == -1, "ballwasm.js's %d sizes and offsets are wasm32's: %s" % (len(glue), glue))

        # 3. the C++ probe: libc++'s containers over libball; the memory grows under it
        n = 100000
        history = browser.evaluate("ball.exports.wasm_probe_history(%d)" % n)
        grown = browser.evaluate("ball.exports.memory.buffer.byteLength")
        check(history == 64 * n - 2080 and grown > got["bytes"],
              "C++ probe (std::map, std::vector, std::deque): %s for n = %d, want %d; memory %d -> %d bytes"
              % (history, n, 64 * n - 2080, got["bytes"], grown))

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
