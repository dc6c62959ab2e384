#!/usr/bin/env python3
"""Reads an LCM log written by lcm-logger (Debian's liblcm-bin; the log format is LCM's own:
per event a sync word, event number, receive time in microseconds, channel and payload) and
checks channels' messages: their number, their rate from the receive times, and for
headingd.heading_t (HEADING) the share of estimates marked VALIDITY_FRESH. No LCM Python
module is needed (Debian 12 has none): heading_t's validity is the byte after the 8-byte
fingerprint and three int64 fields (daemon/lcm/heading_t.lcm).

usage: lcm_log_rate.py LOG CHANNEL [BOUND=VALUE]... [CHANNEL [BOUND=VALUE]...]...
  bounds: min_count=N (default 1), min_hz=F, max_hz=F, min_fresh=F (share of VALIDITY_FRESH)
  e.g.    lcm_log_rate.py run.log HEADING min_hz=80 max_hz=120 min_fresh=0.9 GPS min_count=3
Prints one line per channel, prefixed PASS or FAIL; exits 1 when a bound is not met."""
import struct
import sys

SYNC = 0xEDA1DA01
HEADER = struct.Struct(">IqqII")  # sync, event number, utime, channel length, data length
VALIDITY_OFFSET = 8 + 3 * 8  # fingerprint, utime, sample_utime, sample_age_us
VALIDITY_FRESH = 1


def events(path):
    with open(path, "rb") as f:
        data = f.read()
    pos = 0
    while pos + HEADER.size <= len(data):
        sync, _, utime, channel_len, data_len = HEADER.unpack_from(data, pos)
        if sync != SYNC:
            raise SystemExit(f"lcm_log_rate: {path}: no sync word at byte {pos}")
        pos += HEADER.size
        channel = data[pos:pos + channel_len].decode("utf-8", "replace")
        pos += channel_len
        payload = data[pos:pos + data_len]
        pos += data_len
        if len(payload) == data_len:  # the logger may be stopped mid-event
            yield channel, utime, payload


BOUNDS = {"min_count": int, "min_hz": float, "max_hz": float, "min_fresh": float}


def parse_checks(words):
    """CHANNEL [BOUND=VALUE]... groups, in order."""
    checks = []
    for word in words:
        if "=" not in word:
            checks.append((word, {"min_count": 1}))
            continue
        key, value = word.split("=", 1)
        if not checks or key not in BOUNDS:
            raise SystemExit(f"lcm_log_rate: '{word}': expected a channel, then {', '.join(BOUNDS)}")
        checks[-1][1][key] = BOUNDS[key](value)
    return checks


def check(name, times, fresh, bounds):
    n = len(times)
    span_s = (times[-1] - times[0]) * 1e-6 if n >= 2 else 0.0
    rate = (n - 1) / span_s if span_s > 0 else 0.0
    fresh_share = fresh / n if n else 0.0
    line = f"{name}: {n} messages over {span_s:.2f} s = {rate:.1f} Hz"
    if "min_fresh" in bounds:
        line += f", {100 * fresh_share:.1f} % VALIDITY_FRESH"
    problems = []
    if n < bounds["min_count"]:
        problems.append(f"fewer than {bounds['min_count']} messages")
    if "min_hz" in bounds and rate < bounds["min_hz"]:
        problems.append(f"rate below {bounds['min_hz']} Hz")
    if "max_hz" in bounds and rate > bounds["max_hz"]:
        problems.append(f"rate above {bounds['max_hz']} Hz")
    if "min_fresh" in bounds and fresh_share < bounds["min_fresh"]:
        problems.append(f"fresh share below {100 * bounds['min_fresh']:.0f} %")
    print(("FAIL: " if problems else "PASS: ") + line + ("; " + ", ".join(problems) if problems else ""))
    return not problems


def main():
    if len(sys.argv) < 3:
        raise SystemExit(__doc__)
    log, checks = sys.argv[1], parse_checks(sys.argv[2:])
    times = {name: [] for name, _ in checks}
    fresh = {name: 0 for name, _ in checks}
    for channel, utime, payload in events(log):
        if channel not in times:
            continue
        times[channel].append(utime)
        if len(payload) > VALIDITY_OFFSET and payload[VALIDITY_OFFSET] == VALIDITY_FRESH:
            fresh[channel] += 1
    results = [check(name, times[name], fresh[name], bounds) for name, bounds in checks]
    sys.exit(0 if all(results) else 1)


if __name__ == "__main__":
    main()
