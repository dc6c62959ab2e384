#!/usr/bin/python3
"""tools/python/headingd_listen.py against the real daemon: headingd plays the demo capture
(config/demo.toml) for a few seconds while lcm-logger records the same LCM traffic; every
HEADING and STATUS message in lcm-logger's log must be among the listener's JSON lines with
the same values (so the listener's UDP decoding loses and changes nothing), and its CSV
must hold the same HEADING values. LCM's fragments (LC03) are checked on a STATUS cut up here.

Run in a private network namespace (tests/daemon/in-private-net.sh): the demo's LCM URL is
LCM's default group and port.

  headingd_listen_test.py HEADINGD_BIN REPO_DIR TYPES_DIR
"""
import csv
import importlib.util
import json
import os
import signal
import struct
import subprocess
import sys
import tempfile
import time

LOG_SYNC = 0xEDA1DA01  # LCM log event marker


def read_lcm_log(path):
    """[(channel, payload)] of an LCM log file (event: sync, int64 number, int64 utime,
    int32 channel length, int32 data length, channel, data)."""
    events = []
    with open(path, "rb") as f:
        data = f.read()
    pos = 0
    while pos + 28 <= len(data):
        sync, _, _, channel_len, data_len = struct.unpack_from(">IqqII", data, pos)
        if sync != LOG_SYNC:
            raise ValueError(f"{path}: no event marker at byte {pos}")
        pos += 28
        channel = data[pos:pos + channel_len].decode()
        pos += channel_len
        events.append((channel, data[pos:pos + data_len]))
        pos += data_len
    return events


def main():
    headingd, repo, types_dir = sys.argv[1:4]
    spec = importlib.util.spec_from_file_location("headingd_listen", os.path.join(repo, "tools/python/headingd_listen.py"))
    listen = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(listen)
    types = listen.load_types(types_dir)
    failures = []

    with tempfile.TemporaryDirectory() as tmp:
        log_path, csv_path = os.path.join(tmp, "demo.lcmlog"), os.path.join(tmp, "heading.csv")
        logger = subprocess.Popen(["lcm-logger", "--quiet", "--lcm-url=" + listen.DEFAULT_URL, log_path])
        # Its output into a file: a pipe read only at the end would fill and stop it.
        out_file = open(os.path.join(tmp, "lines.json"), "w+")
        listener = subprocess.Popen([sys.executable, os.path.join(repo, "tools/python/headingd_listen.py"),
                                     "--types", types_dir, "--csv", csv_path], stdout=out_file,
                                    stderr=subprocess.PIPE, text=True)
        time.sleep(0.5)
        daemon = subprocess.Popen([headingd, "--config", os.path.join(repo, "config/demo.toml")],
                                  stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        time.sleep(4.0)
        daemon.send_signal(signal.SIGTERM)
        _, daemon_err = daemon.communicate(timeout=5)
        if daemon.returncode != 0:
            failures.append(f"headingd exited with {daemon.returncode}: {daemon_err}")
        time.sleep(0.5)
        listener.send_signal(signal.SIGINT)
        logger.send_signal(signal.SIGINT)
        _, err = listener.communicate(timeout=5)
        out_file.seek(0)
        out = out_file.read()
        out_file.close()
        logger.wait(timeout=5)
        if listener.returncode != 0:
            failures.append(f"headingd_listen exited with {listener.returncode}: {err}")

        lines = [json.loads(line) for line in out.splitlines()]
        logged = []
        for channel, payload in read_lcm_log(log_path):
            if channel in ("HEADING", "STATUS"):
                cls = types[payload[:8]]
                logged.append({"channel": channel, "type": cls.__name__, **listen.plain(cls.decode(payload))})
        with open(csv_path, newline="") as f:
            rows = list(csv.DictReader(f))
        log_path_copy = os.path.join(os.path.dirname(tmp), os.path.basename(tmp) + ".lcmlog")
        os.replace(log_path, log_path_copy)

    heading_lines = [m for m in lines if m["channel"] == "HEADING"]
    status_lines = [m for m in lines if m["channel"] == "STATUS"]
    logged_status = [m for m in logged if m["channel"] == "STATUS"]
    print(f"listener: {len(heading_lines)} HEADING, {len(status_lines)} STATUS; lcm-logger: "
          f"{len(logged) - len(logged_status)} HEADING, {len(logged_status)} STATUS; CSV rows {len(rows)}; "
          f"{err.strip()}")
    if heading_lines and logged:
        print(f"listener HEADING utime {heading_lines[0]['utime']} .. {heading_lines[-1]['utime']}; lcm-logger "
              f"{logged[0]['utime']} .. {logged[-1]['utime']}")
    if len(heading_lines) < 100 or len(status_lines) < 2:
        failures.append("too few messages for a 4 s run at 100 Hz")
    if any(m["channel"] not in ("HEADING", "STATUS") for m in lines):
        failures.append("a channel that was not asked for was printed")
    if lines != logged:
        failures.append(f"the listener's messages differ from lcm-logger's ({len(lines)} vs {len(logged)})")
    if not any(len(m["sources"]) >= 2 and m["rings"] for m in status_lines):
        failures.append("no STATUS with its sources and rings")
    # headingd's messages fit one datagram (LCM fragments above 64 kB): the fragment path is
    # checked on a STATUS cut into LC03 fragments here, out of order, with a lost one after.
    payload = next(p for c, p in read_lcm_log(log_path_copy) if c == "STATUS")
    fragments = [payload[i:i + 100] for i in range(0, len(payload), 100)]
    datagrams = []
    for n, chunk in enumerate(fragments):
        head = struct.pack(">IIIIHH", listen.MAGIC_FRAGMENT, 7, len(payload), n * 100, n, len(fragments))
        datagrams.append(head + (b"STATUS\0" if n == 0 else b"") + chunk)
    r = listen.Reassembler()
    results = [r.add(d, ("127.0.0.1", 1), 0.0) for d in datagrams[1:] + datagrams[:1]]
    if results[-1] != ("STATUS", payload) or any(results[:-1]):
        failures.append("LC03 fragments were not put back together")
    for d in datagrams[:-1]:  # the same message again, its last fragment lost
        r.add(d, ("127.0.0.1", 1), 10.0)
    r.expire(20.0)
    if r.counts["fragments_lost"] != 1:
        failures.append(f"an incomplete fragmented message was not counted: {r.counts}")
    if len(rows) != len(heading_lines):
        failures.append(f"CSV has {len(rows)} rows for {len(heading_lines)} HEADING messages")
    for row, m in zip(rows, heading_lines):
        for key in ("utime", "heading_true_rad", "heading_mag_rad", "declination_rad", "validity"):
            if m[key] is None:
                if row[key] != "":
                    failures.append(f"CSV {key}: {row[key]!r} for null")
            elif float(row[key]) != float(m[key]):
                failures.append(f"CSV {key}: {row[key]} != {m[key]}")
                break
    os.remove(log_path_copy)
    for f in failures[:10]:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
