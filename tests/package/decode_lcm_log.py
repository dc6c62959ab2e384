#!/usr/bin/python3
"""Reads an LCM log file written by headingd (the file:// provider) and decodes every
HEADING, ATTITUDE, IMU, GPS and STATUS event with the generated Python types (package
`headingd`, lcm-gen --python), then checks what a ten-minute demo capture must give.
Needs no LCM Python binding: the generated classes decode bytes themselves.

  decode_lcm_log.py LOG
"""
import math
import struct
import sys

import headingd  # the generated package, as installed in /usr/lib/python3/dist-packages

SYNC = 0xEDA1DA01
counts = {}
headings = []
with open(sys.argv[1], "rb") as log:
    data = log.read()
offset = 0
while offset < len(data):
    # LCM log event: sync, event number, utime, channel length, data length, channel, data.
    sync, _event, _utime, channel_len, data_len = struct.unpack_from(">IqqII", data, offset)
    assert sync == SYNC, f"bad sync word at byte {offset}"
    offset += 28
    channel = data[offset:offset + channel_len].decode()
    payload = data[offset + channel_len:offset + channel_len + data_len]
    offset += channel_len + data_len
    message_type = {"HEADING": headingd.heading_t, "ATTITUDE": headingd.attitude_t,
                    "STATUS": headingd.status_t, "IMU": headingd.imu_t, "GPS": headingd.gps_t}[channel]
    message = message_type.decode(payload)  # raises ValueError on a fingerprint mismatch
    counts[channel] = counts.get(channel, 0) + 1
    if channel == "HEADING" and message.validity == headingd.heading_t.VALIDITY_FRESH:
        headings.append(message.heading_true_rad)
    if channel == "STATUS":
        last_status = message

print("decoded:", counts)
# Ten minutes at 100 Hz played at 1000x: every IMU sample and GPS epoch, one HEADING per
# 10 ms estimator tick (about 60 in the 0.6 s of play).
assert counts.get("IMU", 0) > 59000, counts
assert counts.get("GPS", 0) > 590, counts
assert counts.get("HEADING", 0) > 10, counts
assert counts.get("STATUS", 0) > 0, counts
assert headings and all(math.isfinite(h) and -math.pi <= h <= 2 * math.pi for h in headings)
assert last_status.state in ("ok", "degraded"), last_status.state
print(f"PASS: {len(headings)} fresh headings decoded in Python, last STATUS {last_status.state!r}")
