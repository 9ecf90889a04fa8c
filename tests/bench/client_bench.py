#!/usr/bin/env python3
"""What a client of the client library costs (docs/client.md, "What it
costs"; ./run bench-client): a ball-server of one match on loopback, a
ball-bot on slot 1, and the C example (examples/c/rally.c) on slot 0, a game
as users write one: it polls and draws the ball 60 times a second (a
ball_net_ball_at each frame and one more for each pose) and pushes its
racket's pose 30 times a second. Measured, in rounds:

- the game's CPU over SECONDS after a warm-up (utime + stime of the whole
  process from /proc, Fast DDS's threads included), in % of one core;
- the payload bytes it took and wrote per second (its ball_net_status);
- net_query: ball_net_ball_at against ball_segment_eval in the same run
  (a spectator client of the same match), the ratio's min and median.

  client_bench.py --bin BUILD --domain N [--seconds 20] [--warmup 3] [--rounds 3] [--states 0|1]
"""
import argparse
import os
import re
import signal
import statistics
import subprocess
import sys
import time

TICK = os.sysconf("SC_CLK_TCK")


def cpu_seconds(pid):
    """utime + stime of a process, s."""
    with open("/proc/%d/stat" % pid) as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / TICK


def start(cmd, log):
    return subprocess.Popen(cmd, stdout=open(log, "w"), stderr=subprocess.STDOUT, start_new_session=True)


def stop(p):
    if p.poll() is None:
        try:
            os.killpg(p.pid, signal.SIGTERM)
            p.wait(10)
        except (ProcessLookupError, subprocess.TimeoutExpired):
            os.killpg(p.pid, signal.SIGKILL)
            p.wait()


def one_round(a, work, k):
    dom = str(a.domain)
    procs = []
    try:
        procs.append(start([a.bin + "/server/ball-server", "--domain", dom, "--matches", "1", "--startup-wait", "0",
                            "--duration", str(a.seconds + a.warmup + 60)], os.path.join(work, "server%d.log" % k)))
        time.sleep(0.5)
        procs.append(start([a.bin + "/server/ball-bot", "--domain", dom, "--match", "0", "--player", "1"],
                           os.path.join(work, "bot%d.log" % k)))
        log = os.path.join(work, "rally%d.log" % k)
        game = start([a.bin + "/examples/rally", "--domain", dom, "--match", "0", "--points", "1000000", "--hits",
                      "1000000", "--seconds", str(a.warmup + a.seconds), "--states", str(a.states)], log)
        procs.append(game)
        time.sleep(a.warmup)
        c0, t0 = cpu_seconds(game.pid), time.monotonic()
        time.sleep(a.seconds - 0.5)
        c1, t1 = cpu_seconds(game.pid), time.monotonic()
        q = subprocess.run([a.bin + "/tests/bench/net_query", "--domain", dom, "--calls", "200000", "--rounds", "9"],
                           capture_output=True, text=True, timeout=120)
        game.wait(a.warmup + a.seconds + 30)
        text = open(log).read()
        m = re.search(r"rally: ([\d.]+) s: (\d+) poses, (\d+) segments, (\d+) events taken; bytes in (\d+), out (\d+)", text)
        r = re.search(r"ratio ball_net_ball_at / ball_segment_eval: min ([\d.]+), median ([\d.]+)", q.stdout)
        ns = re.findall(r"ball_net_ball_at ([\d.]+) ns, ball_segment_eval ([\d.]+) ns", q.stdout)
        if not m or not r or q.returncode != 0:
            print(q.stdout, q.stderr, text[-2000:], file=sys.stderr)
            raise SystemExit("client_bench: a round did not finish")
        secs = float(m.group(1))
        return {"cpu_pct": 100.0 * (c1 - c0) / (t1 - t0), "poses_s": int(m.group(2)) / secs,
                "hits": text.count("(me)"), "in_Bps": int(m.group(5)) / secs, "out_Bps": int(m.group(6)) / secs,
                "ratio_min": float(r.group(1)), "ratio_median": float(r.group(2)),
                "query_ns": min(float(x) for x, _ in ns), "eval_ns": min(float(y) for _, y in ns)}
    finally:
        for p in reversed(procs):
            stop(p)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", required=True, help="the build folder")
    ap.add_argument("--domain", type=int, required=True)
    ap.add_argument("--seconds", type=float, default=20.0)
    ap.add_argument("--warmup", type=float, default=3.0)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--states", type=int, choices=(0, 1), default=0,
                    help="1: the game reads the server's ball states too (ball_net_config.ball_states)")
    a = ap.parse_args()
    work = os.path.join(a.bin, "client-bench")
    os.makedirs(work, exist_ok=True)
    rows = [one_round(a, work, k) for k in range(a.rounds)]
    for k, row in enumerate(rows):
        print("round %d: game CPU %.2f %% of a core (%.1f poses/s, %d hits of its own); bytes in %.0f/s, out %.0f/s; "
              "ball_net_ball_at %.1f ns, ball_segment_eval %.1f ns, ratio min %.3f median %.3f" %
              (k, row["cpu_pct"], row["poses_s"], row["hits"], row["in_Bps"], row["out_Bps"], row["query_ns"],
               row["eval_ns"], row["ratio_min"], row["ratio_median"]))
    med = lambda key: statistics.median(r[key] for r in rows)
    print("client_bench: ball states %s; %d rounds of %g s: game CPU min %.2f %%, median %.2f %% of a core; bytes in %.0f/s, out "
          "%.0f/s (median); ball query / ball_segment_eval min %.3f, median %.3f" %
          ("read" if a.states else "not read", a.rounds, a.seconds, min(r["cpu_pct"] for r in rows), med("cpu_pct"), med("in_Bps"), med("out_Bps"),
           min(r["ratio_min"] for r in rows), med("ratio_median")))


if __name__ == "__main__":
    main()
