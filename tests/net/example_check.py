#!/usr/bin/env python3
"""An example game of examples/ against a ball-server and a ball-bot on loopback (ctest's
net_example_c and net_example_cpp): a server of one match, a bot in its slot 1, the example
with --points 3; passed when the example exits 0 with at least one "(me)" hit in its output.
Every process is started in a group of its own, dies with this script (PR_SET_PDEATHSIG) and is
stopped at its end, also on a failure; no Fast DDS file may be left in /dev/shm.

  example_check.py --bin DIR --example PATH --domain ID --work DIR
"""
import argparse
import ctypes
import os
import shutil
import signal
import subprocess
import sys
import time

LIBC = ctypes.CDLL(None)
PR_SET_PDEATHSIG = 1


def start(args, log, **kw):
    """A process in a group of its own that dies with this script."""
    with open(log, "w") as out:
        return subprocess.Popen(args, stdout=out, stderr=subprocess.STDOUT, start_new_session=True,
                                preexec_fn=lambda: LIBC.prctl(PR_SET_PDEATHSIG, signal.SIGKILL), **kw)


def stop(p, wait=10.0):
    """SIGTERM to its group, SIGKILL after `wait` s; its exit status (a signal: negative)."""
    if p.poll() is None:
        try:
            os.killpg(p.pid, signal.SIGTERM)
            p.wait(wait)
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGKILL)
            p.wait()
        except ProcessLookupError:
            p.wait()
    return p.returncode


def dds_shm():
    """Fast DDS's shared-memory files (the QoS profiles turn shared memory off: there are none)."""
    prefixes = ("fastrtps_", "fast_datasharing", "sem.fastrtps_", "sem.fast_datasharing")
    return {n for n in os.listdir("/dev/shm") if n.startswith(prefixes)}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", required=True, help="the folder of ball-server and ball-bot")
    ap.add_argument("--example", required=True)
    ap.add_argument("--domain", type=int, required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--points", type=int, default=3)
    a = ap.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    name = os.path.basename(a.example)
    failures = []

    def check(ok, text):
        print(("ok   " if ok else "FAIL ") + text, flush=True)
        if not ok:
            failures.append(text)

    shm_before = dds_shm()
    procs = []
    try:
        # (bounded by their --duration too, should this script be killed before its end)
        procs.append(start([a.bin + "/ball-server", "--domain", str(a.domain), "--matches", "1", "--startup-wait", "0",
                            "--duration", "85"], os.path.join(a.work, "server.log")))
        procs.append(start([a.bin + "/ball-bot", "--domain", str(a.domain), "--match", "0", "--player", "1",
                            "--duration", "80"], os.path.join(a.work, "bot.log")))
        log = os.path.join(a.work, name + ".log")
        began = time.monotonic()
        game = start([a.example, "--domain", str(a.domain), "--match", "0", "--points", str(a.points),
                      "--seconds", "60"], log)
        procs.append(game)
        try:
            rc = game.wait(75)
        except subprocess.TimeoutExpired:
            rc = None
        seconds = time.monotonic() - began
        with open(log) as f:
            out = f.read()
        print(out, end="", flush=True)
        own = sum(1 for line in out.splitlines() if line.startswith("rally: hit by slot") and "(me)" in line)
        points = sum(1 for line in out.splitlines() if line.startswith("rally: point to side"))
        check(rc == 0, "%s exited with status %s after %.1f s" % (name, rc if rc is not None else "- (killed at 75 s)",
                                                                 seconds))
        check(points >= a.points, "%d points played (at least %d)" % (points, a.points))
        check(own >= 1, '%d hits of its own, "(me)" (at least 1)' % own)
    finally:
        for p in reversed(procs):
            stop(p)
    left = dds_shm() - shm_before
    check(not left, "Fast DDS files left in /dev/shm: " + ", ".join(sorted(left)) if left else
          "no Fast DDS file left in /dev/shm")
    print("example_check: %s" % ("FAILED" if failures else "passed"), flush=True)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
