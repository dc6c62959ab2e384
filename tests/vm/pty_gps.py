#!/usr/bin/env python3
"""A GPS receiver on a pseudo-terminal, for the systemd VM test: opens a pty, gives its slave
side to a group (dialout, the daemon's serial group) with mode 0660, links it under a stable
name (/dev/gps0, what a udev rule gives a real receiver) and writes an NMEA capture into it
one epoch per second (an epoch: the sentences sharing one UTC time; sentences without a time,
such as VTG, go with the epoch before them), looping at the end of the file.

usage: pty_gps.py NMEA_FILE LINK [--group NAME]
Runs until killed; removes LINK on SIGTERM/SIGINT."""
import argparse
import grp
import os
import pty
import signal
import sys
import time
import tty

TIMED_SENTENCES = ("GGA", "RMC", "GLL", "ZDA", "GNS")


def epochs(lines):
    """Groups NMEA sentences by their UTC field."""
    group, current = [], None
    for line in lines:
        fields = line.split(",")
        utc = fields[1] if len(fields) > 1 and fields[0][3:6] in TIMED_SENTENCES else None
        if utc is not None and utc != current and group:
            yield group
            group = []
        if utc is not None:
            current = utc
        group.append(line)
    if group:
        yield group


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("nmea")
    parser.add_argument("link")
    parser.add_argument("--group", default="dialout")
    args = parser.parse_args()

    with open(args.nmea, encoding="ascii") as f:
        sentences = [l.strip() for l in f if l.startswith("$")]
    groups = list(epochs(sentences))
    if not groups:
        sys.exit(f"pty_gps: no NMEA sentences in {args.nmea}")

    master, slave = pty.openpty()
    tty.setraw(slave)  # no echo, no CR/LF translation: the bytes as a receiver sends them
    slave_path = os.ttyname(slave)
    os.chown(slave_path, -1, grp.getgrnam(args.group).gr_gid)
    os.chmod(slave_path, 0o660)
    if os.path.lexists(args.link):
        os.unlink(args.link)
    os.symlink(slave_path, args.link)

    def stop(*_):
        if os.path.islink(args.link):
            os.unlink(args.link)
        sys.exit(0)

    signal.signal(signal.SIGTERM, stop)
    signal.signal(signal.SIGINT, stop)
    print(f"pty_gps: {args.link} -> {slave_path}, {len(groups)} epochs from {args.nmea}", flush=True)

    # The slave side is closed here: the daemon is its only reader, and an exclusive open
    # (TIOCEXCL) by the daemon ends with the daemon's close. While nobody reads (a restart),
    # the kernel keeps a few kB and non-blocking writes beyond that are dropped, as a
    # receiver talking to nobody.
    os.close(slave)
    os.set_blocking(master, False)
    start = time.monotonic()
    n = 0
    while True:
        for group in groups:
            try:
                os.write(master, "".join(s + "\r\n" for s in group).encode("ascii"))
            except (BlockingIOError, OSError):
                pass
            n += 1
            time.sleep(max(0.0, start + n - time.monotonic()))


if __name__ == "__main__":
    main()
