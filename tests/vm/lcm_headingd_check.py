#!/usr/bin/env python3
"""Checks what headingd published, from an LCM log written by lcm-logger (Debian's
liblcm-bin). Debian 12 has no LCM Python module, so the log (per event: sync word, event
number, receive time in us, channel, payload) and the few fields needed are decoded here
from the message definitions in daemon/lcm/*.lcm (big-endian, an 8-byte fingerprint first,
nested structs without one, strings as int32 length with the NUL, then the bytes).

  HEADING  count and rate from the receive times; share of VALIDITY_FRESH (the IMU flows)
  STATUS   rate_hz (the configured tick rate), ticks and deadline_misses: between the first
           and the last STATUS of the log, every tick period must be a tick or a counted
           missed deadline (the loop keeps its 100 Hz schedule), and there must be one
           HEADING per tick (none lost on the way); the last STATUS must report SCHED_FIFO
           for the estimator and the driver threads and memory locked (real time by
           default: the unit grants what the shipped [realtime] asks for)
  GPS      at least --min-gps epochs

usage: lcm_headingd_check.py LOG [--min-heading-hz F] [--min-fresh F] [--min-gps N]
Prints PASS/FAIL lines; exits 1 when a check fails."""
import argparse
import struct
import sys

SYNC = 0xEDA1DA01
EVENT_HEADER = struct.Struct(">IqqII")  # sync, event number, receive utime, channel len, data len


def events(path):
    with open(path, "rb") as f:
        data = f.read()
    pos = 0
    while pos + EVENT_HEADER.size <= len(data):
        sync, _, utime, channel_len, data_len = EVENT_HEADER.unpack_from(data, pos)
        if sync != SYNC:
            raise SystemExit(f"lcm_headingd_check: {path}: no sync word at byte {pos}")
        pos += EVENT_HEADER.size
        channel = data[pos:pos + channel_len].decode("utf-8", "replace")
        payload = data[pos + channel_len:pos + channel_len + data_len]
        pos += channel_len + data_len
        if len(payload) == data_len:  # the logger may be stopped mid-event
            yield channel, utime, payload


class Reader:
    def __init__(self, payload):
        self.b, self.pos = payload, 8  # after the fingerprint

    def take(self, fmt):
        value = struct.unpack_from(">" + fmt, self.b, self.pos)[0]
        self.pos += struct.calcsize(">" + fmt)
        return value

    def string(self):
        n = self.take("i")
        self.pos += n
        return self.b[self.pos - n:self.pos - 1].decode("utf-8", "replace")


def heading_fresh(payload):
    """heading_t: utime, sample_utime, sample_age_us, then int8 validity (1 = FRESH)."""
    return len(payload) > 32 and payload[32] == 1


def status_schedule(payload):
    """status_t up to ticks and deadline_misses (daemon/lcm/status_t.lcm)."""
    r = Reader(payload)
    r.take("q")  # utime
    r.string(), r.string()  # state, reason
    uptime_us = r.take("q")
    for _ in range(r.take("i")):  # source_status_t: name, kind, state, last_error, counters
        for _ in range(4):
            r.string()
        for _ in range(r.take("i")):
            r.string(), r.take("q")
    for _ in range(r.take("i")):  # ring_status_t: name, capacity, high_water, window_high_water, pushed, dropped
        r.string(), r.take("i"), r.take("i"), r.take("i"), r.take("q"), r.take("q")
    rate_hz = r.take("d")
    ticks, misses = r.take("q"), r.take("q")
    for _ in range(11):  # jitter, processing, sample age percentiles; message rates
        r.take("d")
    r.take("q")  # publish_errors
    # The real-time settings in use: estimator policy and priority, drivers', memory locked.
    realtime = (r.string(), r.take("i"), r.string(), r.take("i"), r.take("b") != 0)
    return uptime_us, rate_hz, ticks, misses, realtime


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("log")
    parser.add_argument("--min-heading-hz", type=float, default=95.0)
    parser.add_argument("--min-fresh", type=float, default=0.9)
    parser.add_argument("--min-gps", type=int, default=3)
    args = parser.parse_args()

    headings, statuses, gps = [], [], 0
    for channel, utime, payload in events(args.log):
        if channel == "HEADING":
            headings.append((utime, heading_fresh(payload)))
        elif channel == "STATUS":
            statuses.append((utime, status_schedule(payload)))
        elif channel == "GPS":
            gps += 1
    failures = 0

    def report(ok, text):
        nonlocal failures
        failures += not ok
        print(("PASS: " if ok else "FAIL: ") + text)

    n = len(headings)
    span_s = (headings[-1][0] - headings[0][0]) * 1e-6 if n >= 2 else 0.0
    rate = (n - 1) / span_s if span_s > 0 else 0.0
    fresh = sum(f for _, f in headings) / n if n else 0.0
    report(rate >= args.min_heading_hz and fresh >= args.min_fresh,
           f"HEADING: {n} messages over {span_s:.2f} s = {rate:.1f} Hz (at least {args.min_heading_hz:g}), "
           f"{100 * fresh:.1f} % VALIDITY_FRESH (at least {100 * args.min_fresh:g} %)")

    if len(statuses) < 2:
        report(False, f"STATUS: {len(statuses)} message(s), two are needed for the tick schedule")
    else:
        (t0, (up0, rate_hz, ticks0, miss0, _)), (t1, (up1, _, ticks1, miss1, realtime)) = statuses[0], statuses[-1]
        ticks, misses, dt = ticks1 - ticks0, miss1 - miss0, (up1 - up0) * 1e-6
        periods = dt * rate_hz
        report(abs(ticks + misses - periods) <= max(2.0, 0.02 * periods),
               f"STATUS: rate_hz {rate_hz:g}; over {dt:.2f} s of daemon uptime {ticks} ticks + {misses} missed "
               f"deadlines = {ticks + misses} of {periods:.0f} periods (the shortfall from {rate_hz:g} Hz is "
               f"what the daemon counts and logs as missed)")
        between = sum(1 for t, _ in headings if t0 <= t <= t1)
        report(abs(between - ticks) <= max(2, 0.02 * ticks),
               f"HEADING per tick: {between} HEADING between those STATUS messages for {ticks} ticks")
        # Real time by default: the unit grants what the shipped [realtime] asks for.
        policy, priority, driver_policy, driver_priority, locked = realtime
        report(policy == "SCHED_FIFO" and driver_policy == "SCHED_FIFO" and locked,
               f"STATUS: estimator {policy} {priority}, drivers {driver_policy} {driver_priority}, memory locked "
               f"{locked} (expected SCHED_FIFO for both, memory locked)")
    report(gps >= args.min_gps, f"GPS: {gps} epochs (at least {args.min_gps})")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
