#!/usr/bin/env python3
"""./run bench-wan's table: the rows dds_wan_delay's case wrote at each delay
(JSON Lines) as a markdown table on stdout and gnuplot's columns in DAT.

    wan_table.py ROWS.jsonl OUT.dat
"""
import json
import sys


def main():
    rows = [json.loads(line) for line in open(sys.argv[1]) if line.strip()]
    ms = lambda s: s * 1e3
    print("| one way (jitter) ms | relay's mean up / down ms | hits in 20 s | late samples tested | rewinds "
          "| sample-to-segment p50 / p99 at the server ms | at the watcher ms | bounces ahead / late "
          "| bounce lead p50 ms | desync m | hits by the same racket as at 0 ms | largest difference from 0 ms: "
          "time ms, point cm, return m/s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    with open(sys.argv[2], "w") as dat:
        dat.write("# delay_ms server_p50 server_p99 watcher_p50 watcher_p99 lead_p50 hits\n")
        for r in rows:
            print("| %.0f (%.0f) | %.0f / %.0f | %d | %d | %d | %.0f / %.0f | %.0f / %.0f | %d / %d | %.0f | %.3g "
                  "| %d of %d | %.1f, %.1f, %.2f |" % (
                ms(r["delay"]), ms(r["jitter"]), ms(r["relay_up_mean"]), ms(r["relay_down_mean"]), r["hits_20s"],
                r["late_tested"], r["rewinds"], ms(r["sample_to_segment_server_p50"]),
                ms(r["sample_to_segment_server_p99"]), ms(r["sample_to_segment_watcher_p50"]),
                ms(r["sample_to_segment_watcher_p99"]), r["bounces_ahead"], r["bounces_late"],
                ms(r["bounce_lead_p50"]), r["desync"], r["same_racket"], r["hits_compared"],
                ms(r["max_time_difference"]), r["max_point_difference"] * 100, r["max_return_difference"]))
            dat.write("%g %g %g %g %g %g %d\n" % (
                ms(r["delay"]), ms(r["sample_to_segment_server_p50"]), ms(r["sample_to_segment_server_p99"]),
                ms(r["sample_to_segment_watcher_p50"]), ms(r["sample_to_segment_watcher_p99"]),
                ms(r["bounce_lead_p50"]), r["hits_20s"]))


if __name__ == "__main__":
    main()
