#!/usr/bin/env python3
"""A stranger beside the players of the TLS case (docs/deploy.md): a host
with no certificate of the server's CA tries the server's TCP port and its
UDP ports, and writes as JSON what came back.

    wan_stranger.py HOST PORT DOMAIN

- plain: a TCP connection that sends an RTPS participant announcement's
  header and a participant-disposal-shaped submessage in plain bytes, as a
  replayed capture would: any RTPS or RTCP byte back means the server took it;
- tls: a TLS connection that shows no certificate, then the same bytes;
- udp: the same datagram to every RTPS port of the domain (participants 0 to
  31: 7400 + 250 domain + 0, 1, 10 + 2 i, 11 + 2 i); the case checks that the
  server's host has no UDP socket for them to reach (the ICMP answers that
  say so are rate-limited, so the count of refusals here is only a hint).

The replies are read for at most 3 s each. Only HOST (inside the test's
namespaces) is ever addressed.
"""
import json
import socket
import ssl
import struct
import sys
import time


def rtps_bytes():
    # RTPS header (protocol 2.3, vendor 01.0f, a made-up GUID prefix), then a
    # DATA(p[UD]) shaped submessage: the participant's builtin writer with the
    # status info "disposed and unregistered"
    prefix = bytes(range(1, 13))
    header = b"RTPS" + bytes([2, 3, 0x01, 0x0F]) + prefix
    status = struct.pack("<HH", 0x0071, 4) + bytes([0, 0, 0, 3]) + struct.pack("<HH", 1, 0)
    body = struct.pack("<HH", 0, 16) + bytes([0, 1, 0, 0xC7]) + bytes([0, 1, 0, 0xC2]) + struct.pack("<iI", 0, 1)
    body += bytes([0, 3, 0, 0]) + status
    sub = bytes([0x15, 0x07]) + struct.pack("<H", len(body)) + body
    return header + sub


def read_back(sock, limit=3.0):
    sock.settimeout(0.2)
    got = b""
    end = time.monotonic() + limit
    while time.monotonic() < end:
        try:
            chunk = sock.recv(4096)
        except (socket.timeout, BlockingIOError):
            continue
        except (ConnectionError, ssl.SSLError, OSError) as e:
            return got, type(e).__name__
        if not chunk:
            return got, "closed"
        got += chunk
    return got, "open"


def took_it(got):
    return b"RTPS" in got or b"RTCP" in got


def plain(host, port):
    s = socket.create_connection((host, port), timeout=3)
    s.sendall(rtps_bytes())
    got, end = read_back(s)
    s.close()
    return {"connected": True, "bytes_back": len(got), "rtps_back": took_it(got), "end": end}


def tls(host, port):
    ctx = ssl.SSLContext(ssl.PROTOCOL_TLS_CLIENT)
    ctx.check_hostname = False
    ctx.verify_mode = ssl.CERT_NONE
    raw = socket.create_connection((host, port), timeout=3)
    try:
        s = ctx.wrap_socket(raw)
    except (ssl.SSLError, OSError) as e:
        raw.close()
        return {"handshake": False, "rtps_back": False, "end": type(e).__name__}
    try:
        s.sendall(rtps_bytes())
    except (ssl.SSLError, OSError) as e:
        s.close()
        return {"handshake": True, "rtps_back": False, "end": type(e).__name__}
    got, end = read_back(s)
    s.close()
    return {"handshake": True, "bytes_back": len(got), "rtps_back": took_it(got), "end": end}


def udp(host, domain):
    base = 7400 + 250 * domain
    ports = [base, base + 1] + [base + 10 + 2 * i for i in range(32)] + [base + 11 + 2 * i for i in range(32)]
    s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    s.connect((host, ports[0]))
    refused = 0
    for p in ports:
        s.connect((host, p))
        try:
            s.send(rtps_bytes())
            time.sleep(0.01)
            s.send(rtps_bytes())  # the second send reports the first one's ICMP port unreachable
        except ConnectionRefusedError:
            refused += 1
    s.close()
    return {"ports": len(ports), "refused": refused}


def main():
    host, port, domain = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
    out = {"plain": plain(host, port), "tls": tls(host, port), "udp": udp(host, domain)}
    print(json.dumps(out))


if __name__ == "__main__":
    main()
