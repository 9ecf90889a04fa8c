#!/usr/bin/env python3
"""What DDS Security costs (docs/security.md, "What it costs"): the same
rallies with security off and on, alternating in one run. Each round starts a
ball-server hosting MATCHES matches and two ball-bots per match on loopback,
lets them play for SECONDS, and reads the server's CPU time (user + system,
from /proc) and its hit latency (a hit's newest racket sample written -> its
segment written, the server's --stats-json). Prints a Markdown table of min
and median over the rounds and the on/off ratios.

  security_bench.py --bin BUILD/server --certs DIR [--matches 4] [--seconds 15] [--rounds 3] --domain N
"""
import argparse
import json
import os
import signal
import statistics
import subprocess
import sys
import tempfile
import time


def cpu_seconds(pid):
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")  # utime + stime


def one_round(args, secure, work):
    def sec(identity):
        return ["--secure", args.certs, "--identity", identity] if secure else []

    dom = ["--domain", str(args.domain)]
    stats = os.path.join(work, "server.json")
    out = open(os.path.join(work, "log"), "a")
    server = subprocess.Popen([args.bin + "/ball-server", *dom, "--matches", str(args.matches), "--startup-wait", "0",
                               "--quiet", "--stats-json", stats, *sec("server1")], stdout=out, stderr=out)
    bots = []
    time.sleep(1.0)
    for m in range(args.matches):
        for slot, side in ((0, "a"), (1, "b")):
            bots.append(subprocess.Popen([args.bin + "/ball-bot", *dom, "--match", str(m), "--player", str(slot),
                                          "--rate", "30", "--seed", str(2 * m + slot + 1), "-q",
                                          *sec(f"m{m}-{side}")], stdout=out, stderr=out))
    time.sleep(3.0)  # authentication, discovery, the first serves
    cpu0, t0 = cpu_seconds(server.pid), time.monotonic()
    time.sleep(args.seconds)
    cpu = (cpu_seconds(server.pid) - cpu0) / (time.monotonic() - t0)
    for b in bots:
        b.send_signal(signal.SIGTERM)
    for b in bots:
        b.wait(10)
    server.send_signal(signal.SIGTERM)
    rc = server.wait(10)
    if rc != 0:
        sys.exit(f"security_bench: ball-server ended with {rc}; see {work}/log")
    with open(stats) as f:
        r = json.load(f)
    hits = sum(m["hits"] for m in r["matches"])
    return {"cpu": cpu, "p50": r["latency_p50"] * 1e3, "p99": r["latency_p99"] * 1e3, "hits": hits}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", required=True)
    ap.add_argument("--certs", required=True)
    ap.add_argument("--matches", type=int, default=4)
    ap.add_argument("--seconds", type=float, default=15.0)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--domain", type=int, required=True)
    args = ap.parse_args()
    runs = {False: [], True: []}
    with tempfile.TemporaryDirectory(prefix="ball-secbench-") as work:
        for i in range(args.rounds):
            for secure in (False, True):
                r = one_round(args, secure, work)
                runs[secure].append(r)
                print(f"round {i + 1} {'secure' if secure else 'open  '}: server CPU {r['cpu'] * 100:.1f} %, "
                      f"hit latency p50 {r['p50']:.1f} ms p99 {r['p99']:.1f} ms, {r['hits']} hits", file=sys.stderr)
    print(f"{args.matches} matches, {2 * args.matches} bots at 30 Hz, {args.seconds:g} s a round, "
          f"{args.rounds} rounds each, alternating:\n")
    print("| | server CPU (one core) min / median | hit latency p50 min / median | hit latency p99 min / median |")
    print("|---|---|---|---|")
    med = {}
    for secure in (False, True):
        rs = runs[secure]
        row = []
        for key, scale, unit in (("cpu", 100, " %"), ("p50", 1, " ms"), ("p99", 1, " ms")):
            v = [r[key] * scale for r in rs]
            med[(secure, key)] = statistics.median(v)
            row.append(f"{min(v):.1f} / {statistics.median(v):.1f}{unit}")
        print(f"| {'secure' if secure else 'open'} | " + " | ".join(row) + " |")
    ratio = [med[(True, k)] / med[(False, k)] if med[(False, k)] > 0 else float("nan") for k in ("cpu", "p50", "p99")]
    print("| secure / open (medians) | " + " | ".join(f"{x:.2f}" for x in ratio) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
