#!/usr/bin/env python3
"""./run bench-server's bytes table: the rows dds_wan_bytes's case wrote at
each match count (JSON Lines) as a markdown table on stdout.

    bytes_table.py ROWS.jsonl
"""
import json
import sys


def main():
    rows = [json.loads(line) for line in open(sys.argv[1]) if line.strip()]
    if not rows:
        sys.exit("bytes_table.py: no rows in " + sys.argv[1])
    base = rows[0]["player"]
    print("| matches playing | a player of one match, B/s in (against the first row) | a bot reading every match, "
          "B/s in | the server's host, B/s out | per match | match 0's hits in 10 s |")
    print("|---|---|---|---|---|---|")
    for r in rows:
        print("| %d | %.0f (x%.3f) | %.0f | %.0f | %.0f | %d |" % (
            r["matches"], r["player"], r["player"] / base, r["every_match"], r["server"],
            r["server"] / r["matches"], r["hits"]))


if __name__ == "__main__":
    main()
