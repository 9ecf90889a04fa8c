#!/usr/bin/env python3
"""What hits at their instant cost the server (docs/server-design.md, "Hits at their
instant"), in instructions counted by callgrind: the same on every run, where
CPU time on a shared machine varies by more than the difference.

- The match work: ball_hit_cost plays 12 offline rallies of 30 s (the three
  levels, two bots at 30 Hz) frame-locked and at the instant; counted are the
  calls the server loop makes into a match (frame, on_sample, compensate,
  hit_after, step_to_hit), per match second.
- The whole server (with --server): ball-server hosting MATCHES matches under
  callgrind (every thread: Fast DDS's receive threads too) while ball-load's
  bots play them for SECONDS, per match frame. The rallies are real, so the
  two runs differ in their hits; valgrind slows the server about 50 times, so
  keep MATCHES small.

  hit_cost.py --bin BUILD [--server --domain N [--matches 10] [--seconds 30] [--rounds 3]]
"""
import argparse
import json
import os
import re
import signal
import statistics
import subprocess
import sys
import tempfile
import time

CALLS = ("frame", "on_sample", "compensate", "hit_after", "step_to_hit")


def inclusive(out_file):
    """{function: inclusive Ir} and the program's total, from callgrind_annotate."""
    text = subprocess.run(["callgrind_annotate", "--inclusive=yes", "--threshold=100", out_file],
                          capture_output=True, text=True, check=True).stdout
    total, costs = None, {}
    for line in text.splitlines():
        m = re.match(r"\s*([\d,]+) \(\s*[\d.]+%\)\s+(\S.*)$", line)
        if not m or "=>" in line:
            continue
        ir, what = int(m.group(1).replace(",", "")), m.group(2)
        if what.startswith("PROGRAM TOTALS"):
            total = ir
        f = re.search(r"ballsrv::Match::(\w+)\(", what)
        if f and f.group(1) in CALLS and ":" in what.split("ballsrv::")[0]:
            costs[f.group(1)] = max(costs.get(f.group(1), 0), ir)
    return total, costs


def callgrind(cmd, out_file, **kw):
    return subprocess.Popen(["valgrind", "--tool=callgrind", "--callgrind-out-file=" + out_file, *cmd],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, **kw)


def offline(args, work):
    rows = {}
    for instant in ("false", "true"):
        out_file = os.path.join(work, f"offline.{instant}.out")
        p = callgrind([args.bin + "/tests/ball_hit_cost", "--hit-instant", instant], out_file)
        said = [l for l in p.communicate()[0].splitlines() if not l.startswith("==")]
        if p.returncode != 0:
            sys.exit("hit_cost: ball_hit_cost failed:\n" + "\n".join(said))
        m = re.search(r"([\d.]+) match s", said[-1])
        _, costs = inclusive(out_file)
        rows[instant] = (float(m.group(1)), costs, said[-1])
    print("## the match work (12 offline rallies of 30 s), instructions per match second")
    print(f"{'call':<14}{'frame-locked':>14}{'at the instant':>16}")
    sums = {}
    for instant in ("false", "true"):
        seconds, costs, _ = rows[instant]
        sums[instant] = sum(costs.values()) / seconds
    for call in CALLS:
        a = rows["false"][1].get(call, 0) / rows["false"][0]
        b = rows["true"][1].get(call, 0) / rows["true"][0]
        print(f"{call:<14}{a:>14.0f}{b:>16.0f}")
    print(f"{'all':<14}{sums['false']:>14.0f}{sums['true']:>16.0f}   at the instant / frame-locked "
          f"{sums['true'] / sums['false']:.3f}")
    for instant in ("false", "true"):
        print("  " + rows[instant][2])


def server_run(args, work, instant, k):
    """One run of the whole server under callgrind: (frames, hit wakes, overruns, instructions)."""
    out_file = os.path.join(work, f"server.{instant}.{k}.out")
    stats = os.path.join(work, f"server.{instant}.{k}.json")
    dom = ["--domain", str(args.domain)]
    srv = callgrind([args.bin + "/server/ball-server", *dom, "--matches", str(args.matches), "--state-rate", "10",
                     "--startup-wait", "0", "--quiet", "--hit-instant", instant, "--stats-json", stats], out_file)
    try:
        time.sleep(8.0)  # valgrind starts slowly
        load = subprocess.run([args.bin + "/server/ball-load", *dom, "--matches", str(args.matches), "--warmup", "4",
                               "--duration", str(args.seconds)], capture_output=True, text=True,
                              timeout=args.seconds + 120)
        if load.returncode != 0:
            sys.exit("hit_cost: ball-load failed:\n" + load.stdout + load.stderr)
    finally:
        srv.send_signal(signal.SIGINT)
        srv.communicate(timeout=120)
    with open(stats) as f:
        s = json.load(f)
    total, _ = inclusive(out_file)
    os.remove(out_file)
    return s["frames"], s.get("hit_wakes", 0), s.get("overruns", 0), total


def server(args, work):
    """--rounds interleaved pairs; min and median of each mode's instructions per frame. Under
    valgrind the server runs about 50 times slower: a run whose frames overran (the loop fell
    behind and caught up) does more per frame, so the overruns are shown."""
    print(f"\n## the whole server, {args.matches} matches under callgrind, bots for {args.seconds:g} s, "
          f"{args.rounds} interleaved rounds: instructions per match frame")
    print(f"{'round':<6}{'hit_instant':<12}{'frames':>9}{'hit steps':>10}{'overruns':>9}{'instructions':>15}"
          f"{'per frame':>11}")
    per = {"false": [], "true": []}
    for k in range(args.rounds):
        for instant in ("false", "true"):
            frames, wakes, overruns, total = server_run(args, work, instant, k)
            per[instant].append(total / frames)
            print(f"{k + 1:<6}{instant:<12}{frames:>9}{wakes:>10}{overruns:>9}{total:>15,}{total / frames:>11.0f}",
                  flush=True)
    lo = {m: min(v) for m, v in per.items()}
    mid = {m: statistics.median(v) for m, v in per.items()}
    print(f"per frame, min / median: frame-locked {lo['false']:.0f} / {mid['false']:.0f}, at the instant "
          f"{lo['true']:.0f} / {mid['true']:.0f}")
    print(f"at the instant / frame-locked {lo['true'] / lo['false']:.3f} (min) / {mid['true'] / mid['false']:.3f} "
          "(median)")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", required=True, help="the build folder")
    ap.add_argument("--server", action="store_true", help="also the whole server under callgrind (DDS, loopback)")
    ap.add_argument("--domain", type=int, help="with --server: the DDS domain id")
    ap.add_argument("--matches", type=int, default=10)
    ap.add_argument("--seconds", type=float, default=30.0)
    ap.add_argument("--rounds", type=int, default=3, help="with --server: interleaved pairs of runs")
    args = ap.parse_args()
    if args.server and args.domain is None:
        ap.error("--server needs --domain")
    with tempfile.TemporaryDirectory(prefix="hit-cost-") as work:
        offline(args, work)
        if args.server:
            server(args, work)


if __name__ == "__main__":
    main()
