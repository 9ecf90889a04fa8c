#!/usr/bin/env python3
"""What the DDS Security test (tests/server/itest.cpp, case `secure`) asks of
a loopback capture (docs/security.md, "What the tests show"). Reads pcap files
with scapy (Debian's python3-scapy); prints one JSON object.

  wire_check.py scan PCAP RECORD
      how often the capture holds, in plaintext, the topic names and the ball
      positions of a watcher's record (each as the 8 little-endian bytes of
      its double, as CDR puts it on the wire)

  wire_check.py forge OPEN_PCAP DOMAIN [--prefix HEX] [--match ID] [--count N] [--leave] [--sender HEX]
      takes a plaintext racket sample (RacketSample, docs/protocol.md) from a
      capture of an open domain, rewrites its match id (default 999999) and
      its sequence numbers, puts the participant GUID prefix HEX (default:
      the writer's own) into the RTPS header and sends it N times to every
      user unicast port of DOMAIN's first 8 participants on 127.0.0.1; with
      --leave a control (MatchControl) instead, made a LEAVE of slot 0; with
      --sender only from the datagrams of that participant

  wire_check.py spdp PCAP DOMAIN [--count N] [--lease S] [--rate R]
      takes a participant announcement (an SPDP DATA) from a capture of an
      open domain and sends it again N times, R a second, each time under a
      fresh made-up GUID prefix and with a lease of S seconds, to every
      metatraffic unicast port of DOMAIN's first 8 participants on 127.0.0.1:
      N participants that do not exist
"""
import argparse
import json
import socket
import struct
import sys
import time

from scapy.all import RawPcapReader  # noqa: E402

TOPICS = ["ball/ball_state", "ball/racket_samples", "ball/match_control", "ball/match_info", "ball/segments"]
RTPS_HEADER = 20          # "RTPS", version, vendor, GUID prefix (12)
DATA = 0x15               # the DATA submessage id
RACKET_PAYLOAD = 4 + 72   # encapsulation + RacketSample in XCDR1 (docs/protocol.md)
CONTROL_PAYLOAD = 4 + 68  # encapsulation + MatchControl
CONTROL_LEAVE = 2         # ControlKind (idl/ball.idl)


def udp_payloads(pcap):
    """(payload, destination port) of every UDP datagram over IPv4 of a
    capture of the loopback (Ethernet framing, as tcpdump -i lo writes it);
    read raw, without scapy's dissection, which takes minutes on a capture
    of a secure rally."""
    for frame, _ in RawPcapReader(pcap):
        if len(frame) < 14 + 20 + 8 or frame[12:14] != b"\x08\x00":
            continue
        ip = frame[14:]
        if ip[9] != 17:  # not UDP
            continue
        udp = ip[(ip[0] & 0x0F) * 4:]
        (dport, length) = struct.unpack(">2xHH", udp[:6])
        yield bytes(udp[8:length]), dport


def scan(args):
    raw = b"".join(p for p, _ in udp_payloads(args.pcap))
    positions = []
    with open(args.record) as f:
        for line in f:
            j = json.loads(line)
            if j.get("type") == "state":
                positions.append(j["position"])
    # a double of a CDR payload starts 4-byte aligned in its datagram (RTPS
    # submessages are), so each datagram is looked at in 8-byte windows, 4 apart
    needles = {struct.pack("<d", c) for pos in positions for c in pos if c != 0.0}
    seen = set()
    for datagram, _ in udp_payloads(args.pcap):
        for off in range(0, len(datagram) - 7, 4):
            w = datagram[off:off + 8]
            if w in needles:
                seen.add(w)
    found = sum(any(struct.pack("<d", c) in seen for c in pos if c != 0.0) for pos in positions)
    return {
        "bytes": len(raw),
        "rtps": raw.count(b"RTPS"),
        "topics": {t: raw.count(t.encode()) for t in TOPICS},
        "positions": len(positions),
        "positions_found": found,
    }


def data_submessages(datagram):
    """(flags, endian, body, end) of every DATA submessage of an RTPS datagram."""
    if len(datagram) < RTPS_HEADER or datagram[:4] != b"RTPS":
        return
    i = RTPS_HEADER
    while i + 4 <= len(datagram):
        sid, flags = datagram[i], datagram[i + 1]
        endian = "<" if flags & 1 else ">"
        (length,) = struct.unpack(endian + "H", datagram[i + 2:i + 4])
        body = i + 4
        end = len(datagram) if length == 0 else body + length
        if sid == DATA:
            yield flags, endian, body, end
        i = end


def racket_samples(datagram, size=RACKET_PAYLOAD):
    """(offset of the serialized payload, offset of writerSN) of every DATA
    submessage of the datagram whose payload is `size` bytes (a
    RacketSample's, or a MatchControl's)."""
    out = []
    for flags, endian, body, end in data_submessages(datagram):
        if not flags & 0x02:  # no inline QoS
            (to_qos,) = struct.unpack(endian + "H", datagram[body + 2:body + 4])
            payload = body + 4 + to_qos
            if end - payload == size:
                out.append((payload, body + 12))
    return out


def forge(args):
    found = None
    size = CONTROL_PAYLOAD if args.leave else RACKET_PAYLOAD
    for datagram, port in udp_payloads(args.pcap):
        if args.sender and datagram[8:20].hex() != args.sender:
            continue
        samples = racket_samples(datagram, size)
        if samples:
            found = (bytearray(datagram), samples)
    if found is None:
        return {"forged": 0, "error": "no plaintext racket sample in " + args.pcap}
    d, samples = found
    writer_prefix = bytes(d[8:20]).hex()
    if args.prefix:
        d[8:20] = bytes.fromhex(args.prefix)
    for payload, sn in samples:
        # the writer's sequence number ahead: never a duplicate (a control's the
        # next one: its reliable reader takes it at once, without a gap)
        high, low = struct.unpack("<iI", d[sn:sn + 8])
        low += 1 if args.leave else 50
        d[sn:sn + 8] = struct.pack("<iI", high + (low >> 32), low & 0xFFFFFFFF)
        if args.leave:  # MatchControl: match_id, seq, kind, player: slot 0 given up
            d[payload + 12:payload + 16] = struct.pack("<I", CONTROL_LEAVE)
            d[payload + 16:payload + 18] = struct.pack("<h", 0)
            continue
        d[payload + 4:payload + 8] = struct.pack("<I", args.match)
        (seq,) = struct.unpack("<I", d[payload + 12:payload + 16])
        d[payload + 12:payload + 16] = struct.pack("<I", (seq + 100000) & 0xFFFFFFFF)
    ports = [7400 + 250 * args.domain + 11 + 2 * p for p in range(8)]
    s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    for _ in range(args.count):
        for port in ports:
            s.sendto(bytes(d), ("127.0.0.1", port))
    return {"forged": len(samples), "writer_prefix": writer_prefix, "prefix": bytes(d[8:20]).hex(),
            "ports": ports, "sent": args.count * len(ports)}


SPDP_WRITER = bytes([0x00, 0x01, 0x00, 0xC2])  # the builtin participant writer's entity id
PID_LEASE = 0x0002


def announcements(datagram):
    """(offset of the serialized payload, its end) of every SPDP DATA of a datagram."""
    out = []
    for flags, endian, body, end in data_submessages(datagram):
        if datagram[body + 8:body + 12] != SPDP_WRITER:
            continue
        (to_qos,) = struct.unpack(endian + "H", datagram[body + 2:body + 4])
        payload = body + 4 + to_qos
        if flags & 0x02:  # inline QoS first: a parameter list up to its sentinel
            q = payload
            while q + 4 <= end:
                pid, plen = struct.unpack(endian + "HH", datagram[q:q + 4])
                q += 4 + plen
                if pid == 0x0001:
                    break
            payload = q
        out.append((payload, end))
    return out


def set_lease(d, payload, end, seconds):
    """Puts `seconds` into the announcement's PID_PARTICIPANT_LEASE_DURATION."""
    endian = "<" if d[payload + 1] in (0x01, 0x03) else ">"  # PL_CDR_LE / CDR_LE
    q = payload + 4
    while q + 4 <= end:
        pid, plen = struct.unpack(endian + "HH", d[q:q + 4])
        if pid == 0x0001:
            return False
        if pid == PID_LEASE and plen >= 8:
            d[q + 4:q + 12] = struct.pack(endian + "iI", seconds, 0)
            return True
        q += 4 + plen
    return False


def spdp(args):
    template = None
    for datagram, _ in udp_payloads(args.pcap):
        found = announcements(datagram)
        if found:
            template = (bytearray(datagram), found[0])
            break
    if template is None:
        return {"sent": 0, "error": "no participant announcement in " + args.pcap}
    d, (payload, end) = template
    if not set_lease(d, payload, end, args.lease):
        return {"sent": 0, "error": "no lease in the announcement"}
    prefix = bytes(d[8:20])
    ports = [7400 + 250 * args.domain + 10 + 2 * p for p in range(8)]
    s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    start = time.monotonic()
    for n in range(args.count):
        fresh = bytes([0x01, 0x0F]) + struct.pack(">I", 0xBA110000 + n) + struct.pack(">IH", n * 2654435761 & 0xFFFFFFFF, 7)
        out = bytes(d).replace(prefix, fresh)  # the header's, the GUID's and the key hash's
        for port in ports:
            s.sendto(out, ("127.0.0.1", port))
        delay = start + (n + 1) / args.rate - time.monotonic()
        if delay > 0:
            time.sleep(delay)
    return {"sent": args.count, "template_prefix": prefix.hex(), "seconds": round(time.monotonic() - start, 3),
            "ports": ports}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="verb", required=True)
    a = sub.add_parser("scan")
    a.add_argument("pcap")
    a.add_argument("record")
    b = sub.add_parser("forge")
    b.add_argument("pcap")
    b.add_argument("domain", type=int)
    b.add_argument("--prefix", default="")
    b.add_argument("--match", type=int, default=999999)
    b.add_argument("--count", type=int, default=5)
    b.add_argument("--leave", action="store_true", help="a control instead: LEAVE of slot 0")
    b.add_argument("--sender", default="", help="only datagrams of this GUID prefix (hex)")
    c = sub.add_parser("spdp")
    c.add_argument("pcap")
    c.add_argument("domain", type=int)
    c.add_argument("--count", type=int, default=1000)
    c.add_argument("--lease", type=int, default=3)
    c.add_argument("--rate", type=float, default=1000.0)
    args = ap.parse_args()
    out = {"scan": scan, "forge": forge, "spdp": spdp}[args.verb](args)
    print(json.dumps(out))
    return 0 if "error" not in out else 1


if __name__ == "__main__":
    sys.exit(main())
