#!/usr/bin/env python3
"""The spectator page against hostile HTTP (docs/bots-and-watchers.md, "The
page against hostile HTTP"): a ball-watch --http on loopback, attacked from
other loopback addresses (127.0.0.2 and up: the kernel routes all of 127/8 to
lo), while a real HTTP client (Python's http.client) loads the page from
127.0.0.1. Every attack is bounded in count and time; every check prints its
numbers.

  1. header lines as fast as they go, 4 connections for 6 s: the watcher's
     memory grows by less than 64 MB and is back within 16 MB of where it was
     once they close; the page loads during the attack;
  2. slow headers (a byte every 4 s, and a byte every 0.5 s), 10 connections:
     5 of 5 page loads, each within 3 s; a head that is not whole 5 s after its
     connection opened is closed (measured: at most 6 s);
  3. 500 idle connections from one address: 3 of 3 page loads; of 30 more
     from another address, 14 are closed at once (16 per address);
  4. pages (/stream) from one address: 2, the third told 503; through the
     proxy's address (--http-proxy): 3 pages and 30 connections, none refused;
  5. 128 slow heads from 8 addresses: 40 served, 64 queued, 24 closed at once;
  6. a request of 101 header lines is answered 431; one of 20 kB of headers is
     answered 431 or closed; traversal 404, a long URI 414, a bad range 416.

  http_attack.py --bin DIR --domain ID --work DIR
"""
import argparse
import ctypes
import http.client
import os
import re
import signal
import socket
import subprocess
import sys
import threading
import time

LIBC = ctypes.CDLL(None)
PR_SET_PDEATHSIG = 1
failures = []


def check(ok, text):
    print(("ok   " if ok else "FAIL ") + text, flush=True)
    if not ok:
        failures.append(text)


def rss_mb(pid):
    with open("/proc/%d/status" % pid) as f:
        m = re.search(r"VmRSS:\s+(\d+) kB", f.read())
    return int(m.group(1)) / 1024.0 if m else 0.0


def load_page(port, timeout=3.0):
    """The page as a browser starts it (index, script, module): the seconds it took, or None."""
    t0 = time.monotonic()
    try:
        for path in ("/", "/app.js", "/ball.wasm"):
            c = http.client.HTTPConnection("127.0.0.1", port, timeout=timeout, source_address=("127.0.0.1", 0))
            c.request("GET", path)
            r = c.getresponse()
            body = r.read()
            c.close()
            if r.status != 200 or not body:
                return None
            if time.monotonic() - t0 > timeout:
                return None
    except (OSError, http.client.HTTPException):
        return None
    return time.monotonic() - t0


def attacker(source, port):
    s = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    s.bind((source, 0))
    s.settimeout(2.0)
    s.connect(("127.0.0.1", port))
    return s


def loads_during(port, count, spacing):
    got = []
    for _ in range(count):
        got.append(load_page(port))
        time.sleep(spacing)
    return got


def flood_headers(port, seconds, stop):
    """One connection sending header lines as fast as the server takes them: bytes sent."""
    sent = 0
    try:
        s = attacker("127.0.0.2", port)
        s.settimeout(0.2)
        s.sendall(b"GET / HTTP/1.1\r\nHost: x\r\n")
        line = b"X-Fill: " + b"a" * 90 + b"\r\n"
        chunk = line * 64
        end = time.monotonic() + seconds
        while time.monotonic() < end and not stop.is_set():
            try:
                sent += s.send(chunk)
            except socket.timeout:
                continue
    except OSError:
        pass  # closed by the server: what it should do
    finally:
        try:
            s.close()
        except (OSError, UnboundLocalError):
            pass
    return sent


def attack_memory(port, pid):
    base = rss_mb(pid)
    stop = threading.Event()
    sent = [0] * 4
    threads = [threading.Thread(target=lambda k=k: sent.__setitem__(k, flood_headers(port, 6.0, stop)))
               for k in range(4)]
    peak = base
    for t in threads:
        t.start()
    loads = []
    end = time.monotonic() + 6.5
    while time.monotonic() < end:
        peak = max(peak, rss_mb(pid))
        if len(loads) < 3:
            loads.append(load_page(port))
        time.sleep(0.1)
    stop.set()
    for t in threads:
        t.join()
    time.sleep(2.0)
    after = rss_mb(pid)
    ok_loads = sum(x is not None for x in loads)
    print("header flood: %.0f kB sent on 4 connections; memory %.1f MB before, %.1f at peak, %.1f 2 s after; "
          "%d of %d page loads" % (sum(sent) / 1024.0, base, peak, after, ok_loads, len(loads)), flush=True)
    check(peak - base < 64.0, "a header flood grows the watcher by %.1f MB (< 64)" % (peak - base))
    check(after - base < 16.0, "the memory is given back: %.1f MB above the start 2 s after (< 16)" % (after - base))
    check(ok_loads == len(loads), "the page loads during a header flood: %d of %d" % (ok_loads, len(loads)))


def attack_slow(port):
    socks = []
    for k in range(10):
        try:
            s = attacker("127.0.0.3", port)
            s.sendall(b"GET / HTTP/1.1\r\n")
            socks.append(s)
        except OSError:
            pass
    # the page, five times in 12 s, while each attacker sends a header byte every 4 s
    stop = threading.Event()

    def drip():
        while not stop.wait(4.0):
            for s in socks:
                try:
                    s.send(b"X")
                except OSError:
                    pass

    t = threading.Thread(target=drip)
    t.start()
    loads = loads_during(port, 5, 2.0)
    stop.set()
    t.join()
    for s in socks:
        s.close()
    ok = [x for x in loads if x is not None]
    print("slow headers, 10 connections: %d of 5 page loads, slowest %.2f s"
          % (len(ok), max(ok) if ok else -1.0), flush=True)
    check(len(ok) == 5, "the page loads during slow headers: %d of 5" % len(ok))
    # a head sent a byte every 0.5 s: closed at the deadline
    s = attacker("127.0.0.3", port)
    t0 = time.monotonic()
    s.sendall(b"GET / HTTP/1.1\r\n")
    closed_at = None
    s.settimeout(0.5)
    while time.monotonic() - t0 < 12.0:
        try:
            s.send(b"X")
            if s.recv(4096) == b"":
                closed_at = time.monotonic() - t0
                break
        except socket.timeout:
            continue
        except OSError:
            closed_at = time.monotonic() - t0
            break
    s.close()
    print("a head a byte every 0.5 s: closed after %s s" % ("%.2f" % closed_at if closed_at else "never (12)"),
          flush=True)
    check(closed_at is not None and closed_at <= 6.0, "a slow head is closed at its deadline (<= 6 s)")


def closed_now(s):
    s.setblocking(False)
    try:
        return s.recv(1, socket.MSG_DONTWAIT) == b""
    except BlockingIOError:
        return False
    except OSError:
        return True


def attack_idle(port):
    socks = []
    for k in range(500):
        try:
            socks.append(attacker("127.0.0.4", port))
        except OSError:
            break
    time.sleep(0.5)
    loads = loads_during(port, 3, 1.0)
    ok = [x for x in loads if x is not None]
    print("500 idle connections (%d made): %d of 3 page loads, slowest %.2f s"
          % (len(socks), len(ok), max(ok) if ok else -1.0), flush=True)
    check(len(socks) == 500, "500 idle connections were made (%d)" % len(socks))
    check(len(ok) == 3, "the page loads beside 500 idle connections: %d of 3" % len(ok))
    for s in socks:
        s.close()
    time.sleep(0.5)
    more = [attacker("127.0.0.5", port) for _ in range(30)]
    time.sleep(0.4)  # (within the 1 s a connection may idle)
    shut = sum(closed_now(s) for s in more)
    for s in more:
        s.close()
    print("30 idle connections from one address: %d closed at once" % shut, flush=True)
    check(shut == 14, "beyond 16 connections an address gets none: %d of 30 closed at once (14)" % shut)


def attack_queue(port):
    """128 slow heads from 8 addresses (16 each, their share): 40 served, 64 queued, 24 closed at once."""
    socks = []
    for a in range(8):
        for _ in range(16):
            s = attacker("127.0.1.%d" % (a + 1), port)
            s.sendall(b"GET / HTTP/1.1\r\n")
            socks.append(s)
    time.sleep(0.5)
    shut = sum(closed_now(s) for s in socks)
    for s in socks:
        s.close()
    print("128 slow heads from 8 addresses: %d closed at once" % shut, flush=True)
    check(shut == 24, "a full queue closes what it has no room for: %d of 128 (24: 40 served, 64 queued)" % shut)


def stream_codes(port, source, count):
    conns, codes = [], []
    for _ in range(count):
        c = http.client.HTTPConnection("127.0.0.1", port, timeout=3, source_address=(source, 0))
        try:
            c.request("GET", "/stream")
            codes.append(c.getresponse().status)
        except (OSError, http.client.HTTPException):
            codes.append(None)
        conns.append(c)
    return conns, codes


def shares(port):
    """An address's share of pages (2), and the proxy's (--http-proxy 127.0.0.8): none."""
    conns, codes = stream_codes(port, "127.0.0.7", 3)
    check(codes == [200, 200, 503], "pages from one address: %s (200, 200, 503)" % codes)
    for c in conns:
        c.close()
    conns, codes = stream_codes(port, "127.0.0.8", 3)
    check(codes == [200] * 3, "pages through the proxy's address: %s (200 x 3)" % codes)
    for c in conns:
        c.close()
    more = [attacker("127.0.0.8", port) for _ in range(30)]
    time.sleep(0.4)
    shut = sum(closed_now(s) for s in more)
    for s in more:
        s.close()
    check(shut == 0, "the proxy's address holds 30 connections: %d closed at once (0)" % shut)


def status_of(port, raw):
    s = attacker("127.0.0.6", port)
    s.settimeout(3.0)
    try:
        s.sendall(raw)
        data = s.recv(64)
    except OSError:
        data = b""
    s.close()
    m = re.match(rb"HTTP/1\.[01] (\d+)", data)
    return int(m.group(1)) if m else None


def malformed(port):
    many = b"GET / HTTP/1.1\r\nHost: x\r\n" + b"".join(b"X-%d: y\r\n" % k for k in range(100)) + b"\r\n"
    big = b"GET / HTTP/1.1\r\nHost: x\r\n" + b"".join(b"X-%d: %s\r\n" % (k, b"z" * 2000) for k in range(10)) + b"\r\n"
    cases = [
        ("101 header lines", many, (431,)),
        ("20 kB of headers", big, (400, 431, None)),
        ("a traversal", b"GET /../../etc/passwd HTTP/1.1\r\nHost: x\r\n\r\n", (400, 404)),
        ("a 9 kB URI", b"GET /" + b"a" * 9000 + b" HTTP/1.1\r\nHost: x\r\n\r\n", (414,)),
        ("a range past the end", b"GET /style.css HTTP/1.1\r\nHost: x\r\nRange: bytes=999999-\r\n\r\n", (416,)),
        ("not HTTP", b"\x16\x03\x01\x00\x05hello\r\n\r\n", (400, None)),
    ]
    for name, raw, want in cases:
        got = status_of(port, raw)
        check(got in want, "%s: %s (want %s)" % (name, got, " or ".join(str(w) for w in want)))


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--bin", required=True)
    p.add_argument("--domain", required=True)
    p.add_argument("--work", required=True)
    a = p.parse_args()
    os.makedirs(a.work, exist_ok=True)
    log = os.path.join(a.work, "watch.log")
    w = subprocess.Popen([a.bin + "/ball-watch", "--domain", a.domain, "--http", "0", "--no-log", "--duration",
                          "300", "--http-proxy", "127.0.0.8"], stdout=open(log, "w"), stderr=subprocess.STDOUT, start_new_session=True,
                         preexec_fn=lambda: LIBC.prctl(PR_SET_PDEATHSIG, signal.SIGKILL))
    try:
        port = None
        deadline = time.time() + 20
        while time.time() < deadline and port is None:
            m = re.search(r"the spectator page is at http://[^:]+:(\d+)/", open(log).read())
            port = int(m.group(1)) if m else None
            time.sleep(0.1)
        check(port is not None, "ball-watch serves the page")
        if port is None:
            return 1
        t = load_page(port)
        check(t is not None, "the page loads before any attack (%s s)" % ("%.3f" % t if t else "-"))
        attack_memory(port, w.pid)
        attack_slow(port)
        attack_idle(port)
        malformed(port)
        attack_queue(port)
        time.sleep(6.0)  # (the attacks' connections are gone)
        shares(port)
        check(w.poll() is None, "ball-watch still runs")
        t = load_page(port)
        check(t is not None, "the page loads after every attack")
    finally:
        if w.poll() is None:
            os.killpg(w.pid, signal.SIGTERM)
            try:
                w.wait(10)
            except subprocess.TimeoutExpired:
                os.killpg(w.pid, signal.SIGKILL)
                w.wait()
    if failures:
        print("http_attack: FAIL (%d checks)" % len(failures))
        return 1
    print("http_attack: passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
