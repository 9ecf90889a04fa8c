#!/usr/bin/env python3
"""A TCP relay that delays each direction, for the tests across the internet
(docs/deploy.md): the kernel here has no netem, so the delay of a real path
comes from this program between the players' side and the server.

    delay_relay.py --listen HOST:PORT --to HOST:PORT --delay S --jitter S [--seed N] [--stats FILE]

Every connection made to --listen is relayed to --to. Each chunk read from
one side is written to the other `delay` + a uniform draw in [0, jitter]
seconds after it arrived, but never before the chunk ahead of it (a TCP
stream keeps its order: a late chunk holds the ones behind it, as on a real
path). On SIGTERM it writes what it relayed as JSON to --stats: chunks and
bytes per direction, and the delay each chunk had (mean, max). Only the
addresses given are ever used (the test's namespaces).
"""
import argparse
import asyncio
import json
import random
import signal
import time

stats = {"connections": 0, "up": {"chunks": 0, "bytes": 0, "delay_sum": 0.0, "delay_max": 0.0},
         "down": {"chunks": 0, "bytes": 0, "delay_sum": 0.0, "delay_max": 0.0}}


def address(text):
    host, port = text.rsplit(":", 1)
    return host, int(port)


async def pump(reader, writer, direction, delay, jitter, rng):
    """Reads chunks from reader and writes each to writer when it is due."""
    queue = asyncio.Queue()
    s = stats[direction]

    async def deliver():
        while True:
            due, arrived, chunk = await queue.get()
            if chunk is None:
                break
            wait = due - time.monotonic()
            if wait > 0:
                await asyncio.sleep(wait)
            writer.write(chunk)
            await writer.drain()
            took = time.monotonic() - arrived
            s["chunks"] += 1
            s["bytes"] += len(chunk)
            s["delay_sum"] += took
            s["delay_max"] = max(s["delay_max"], took)
        writer.close()

    sender = asyncio.ensure_future(deliver())
    last_due = 0.0
    try:
        while True:
            chunk = await reader.read(65536)
            if not chunk:
                break
            now = time.monotonic()
            last_due = max(last_due, now + delay + rng.uniform(0.0, jitter))
            queue.put_nowait((last_due, now, chunk))
    except (ConnectionError, OSError):
        pass
    queue.put_nowait((0.0, 0.0, None))
    try:
        await sender
    except (ConnectionError, OSError):
        pass


async def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--listen", required=True)
    parser.add_argument("--to", required=True)
    parser.add_argument("--delay", type=float, default=0.0)
    parser.add_argument("--jitter", type=float, default=0.0)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--stats", default="")
    a = parser.parse_args()
    rng = random.Random(a.seed)
    target = address(a.to)

    async def relay(client_reader, client_writer):
        stats["connections"] += 1
        try:
            server_reader, server_writer = await asyncio.open_connection(*target)
        except OSError:
            client_writer.close()
            return
        await asyncio.gather(pump(client_reader, server_writer, "up", a.delay, a.jitter, rng),
                             pump(server_reader, client_writer, "down", a.delay, a.jitter, rng))

    host, port = address(a.listen)
    server = await asyncio.start_server(relay, host, port)
    stop = asyncio.Event()
    loop = asyncio.get_running_loop()
    for sig in (signal.SIGTERM, signal.SIGINT):
        loop.add_signal_handler(sig, stop.set)
    print("listening", flush=True)
    await stop.wait()
    server.close()
    if a.stats:
        out = {"connections": stats["connections"]}
        for d in ("up", "down"):
            s = stats[d]
            out[d] = {"chunks": s["chunks"], "bytes": s["bytes"], "delay_max": s["delay_max"],
                      "delay_mean": s["delay_sum"] / s["chunks"] if s["chunks"] else 0.0}
        with open(a.stats, "w") as f:
            json.dump(out, f)


if __name__ == "__main__":
    asyncio.run(main())
