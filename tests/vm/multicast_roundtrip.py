#!/usr/bin/env python3
"""Runs where vm-run.sh set up lo: one UDP datagram to LCM's default multicast group with
TTL 0 must loop back to a socket that joined the group (what LCM udpm?ttl=0 needs).
Exits 77 (skipped) when no python3 is there to run it (see the CMake file)."""
import socket
import struct
import sys

GROUP, PORT = "239.255.76.67", 7667
payload = b"headingd-vm multicast check"

receiver = socket.socket(socket.AF_INET, socket.SOCK_DGRAM, socket.IPPROTO_UDP)
receiver.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
receiver.bind(("", PORT))
membership = struct.pack("4s4s", socket.inet_aton(GROUP), socket.inet_aton("0.0.0.0"))
receiver.setsockopt(socket.IPPROTO_IP, socket.IP_ADD_MEMBERSHIP, membership)
receiver.settimeout(5.0)

sender = socket.socket(socket.AF_INET, socket.SOCK_DGRAM, socket.IPPROTO_UDP)
sender.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_TTL, 0)
sender.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_LOOP, 1)
sender.sendto(payload, (GROUP, PORT))

try:
    data, source = receiver.recvfrom(1024)
except socket.timeout:
    print(f"FAIL: nothing received on {GROUP}:{PORT} within 5 s")
    sys.exit(1)
if data != payload:
    print(f"FAIL: received {data!r} from {source}, expected {payload!r}")
    sys.exit(1)
print(f"PASS: multicast {GROUP}:{PORT} ttl=0 round trip on lo ({len(data)} bytes from {source[0]})")
