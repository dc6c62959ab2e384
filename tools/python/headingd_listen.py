#!/usr/bin/python3
"""headingd_listen: print headingd's LCM messages as JSON lines, and optionally write them to CSV.

Debian 12 has no Python binding of LCM (no python3-lcm package), so this script does not use
`import lcm`: it joins the LCM UDP multicast group itself and decodes the datagrams with the
Python message types that `lcm-gen --python` makes from daemon/lcm/*.lcm (the build puts them
in build/daemon/lcmgen/python; the Debian package installs them as the `headingd` package).
A message's type is found by its fingerprint (the first 8 bytes), so any channel decodes.

LCM's UDP transport, as this script reads it (all integers big-endian):
  small message, one datagram:  'LC02' (0x4c433032), uint32 sequence number,
                                channel name NUL-terminated, the encoded message
  large message, fragmented:    'LC03' (0x4c433033), uint32 sequence number, uint32 message
                                size, uint32 offset of this fragment, uint16 fragment number,
                                uint16 fragment count; fragment 0 then has the channel name
                                NUL-terminated; then the fragment's bytes
LCM fragments messages larger than about 64 kB (headingd's own are far smaller); fragments
are put back together per sender and sequence number, and a message whose fragments do not
all arrive within 2 s is dropped and counted. The counts
of datagrams not understood, fragments lost and messages of unknown types are printed to
stderr at the end.

Usage:
  tools/python/headingd_listen.py [--url URL] [--channels HEADING,STATUS] [--csv FILE]
                                  [--csv-channel HEADING] [--count N] [--duration S]
                                  [--types DIR]
Each message is one JSON object per line on stdout: {"channel": ..., "type": ..., and the
message's fields}; nested messages are objects, NaN is null. --csv writes the messages of one
channel (HEADING by default) as rows, one column per field (nested values as JSON text).
"""
import argparse
import csv
import glob
import json
import math
import os
import socket
import struct
import sys
import time
import urllib.parse

MAGIC_SHORT = 0x4C433032  # 'LC02'
MAGIC_FRAGMENT = 0x4C433033  # 'LC03'
DEFAULT_URL = "udpm://239.255.76.67:7667?ttl=0"  # LCM's default group and port
HEADINGD_TYPES = ("heading_t", "attitude_t", "imu_t", "gps_t", "status_t")


def find_types_dir(explicit):
    """The folder holding the `headingd` package of generated types, or None (then the
    installed package is imported from sys.path)."""
    if explicit:
        return explicit
    if os.environ.get("HEADINGD_LCM_PYTHON"):
        return os.environ["HEADINGD_LCM_PYTHON"]
    repo = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    built = glob.glob(os.path.join(repo, "build*", "daemon", "lcmgen", "python", "headingd", "__init__.py"))
    if built:
        return os.path.dirname(os.path.dirname(max(built, key=os.path.getmtime)))
    return None


def load_types(types_dir):
    """{packed fingerprint: message class} of headingd's top-level message types."""
    if types_dir:
        sys.path.insert(0, types_dir)
    import importlib
    types = {}
    for name in HEADINGD_TYPES:
        cls = getattr(importlib.import_module("headingd." + name), name)
        types[cls._get_packed_fingerprint()] = cls
    return types


def parse_url(url):
    """(group, port, ttl) of a udpm:// URL."""
    parsed = urllib.parse.urlparse(url)
    if parsed.scheme != "udpm" or not parsed.hostname or not parsed.port:
        raise ValueError(f"expected udpm://GROUP:PORT[?ttl=N], got {url!r}")
    ttl = int(urllib.parse.parse_qs(parsed.query).get("ttl", ["0"])[0])
    return parsed.hostname, parsed.port, ttl


def open_socket(group, port):
    s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM, socket.IPPROTO_UDP)
    # Beside other subscribers on the same port (lcm-spy, lcm-logger), as LCM itself does on
    # Linux: SO_REUSEADDR, not SO_REUSEPORT (which would share the datagrams out among the
    # sockets instead of giving each a copy).
    s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    s.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4 << 20)
    s.bind(("", port))
    membership = struct.pack("4s4s", socket.inet_aton(group), socket.inet_aton("0.0.0.0"))
    s.setsockopt(socket.IPPROTO_IP, socket.IP_ADD_MEMBERSHIP, membership)
    s.settimeout(0.2)
    return s


class Reassembler:
    """LCM datagrams -> (channel, payload); fragments joined per (sender, sequence number)."""

    def __init__(self):
        self.partial = {}  # (sender, seq) -> [channel, size, bytearray, fragments left, first seen]
        self.counts = {"datagrams": 0, "not_lcm": 0, "fragments_lost": 0}

    def add(self, datagram, sender, now):
        self.counts["datagrams"] += 1
        if len(datagram) < 8:
            self.counts["not_lcm"] += 1
            return None
        magic, seq = struct.unpack_from(">II", datagram, 0)
        if magic == MAGIC_SHORT:
            end = datagram.find(b"\0", 8)
            if end < 0:
                self.counts["not_lcm"] += 1
                return None
            return datagram[8:end].decode("utf-8", "replace"), datagram[end + 1:]
        if magic != MAGIC_FRAGMENT or len(datagram) < 20:
            self.counts["not_lcm"] += 1
            return None
        size, offset, number, count = struct.unpack_from(">IIHH", datagram, 8)
        data_start = 20
        key = (sender, seq)
        if number == 0:
            end = datagram.find(b"\0", 20)
            if end < 0:
                self.counts["not_lcm"] += 1
                return None
            channel = datagram[20:end].decode("utf-8", "replace")
            data_start = end + 1
            entry = self.partial.setdefault(key, [None, size, bytearray(size), count, now])
            entry[0] = channel
        else:
            entry = self.partial.setdefault(key, [None, size, bytearray(size), count, now])
        chunk = datagram[data_start:]
        if offset + len(chunk) > entry[1]:
            self.counts["not_lcm"] += 1
            return None
        entry[2][offset:offset + len(chunk)] = chunk
        entry[3] -= 1
        self.expire(now)
        if entry[3] == 0 and entry[0] is not None:
            del self.partial[key]
            return entry[0], bytes(entry[2])
        return None

    def expire(self, now, max_age_s=2.0):
        for key in [k for k, e in self.partial.items() if now - e[4] > max_age_s]:
            del self.partial[key]
            self.counts["fragments_lost"] += 1


def plain(value):
    """A decoded message's value as JSON-ready data: nested messages as dicts, NaN as None."""
    if hasattr(value, "__slots__"):
        return {name: plain(getattr(value, name)) for name in value.__slots__}
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, bytes):
        return value.hex()
    return value


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--url", default=os.environ.get("LCM_DEFAULT_URL", DEFAULT_URL),
                    help="LCM URL (udpm://GROUP:PORT?ttl=N); default $LCM_DEFAULT_URL, else %(default)s")
    ap.add_argument("--channels", default="HEADING,STATUS",
                    help="comma-separated channels to print (default %(default)s; '*' for all)")
    ap.add_argument("--csv", metavar="FILE", help="also write the messages of --csv-channel to FILE as CSV")
    ap.add_argument("--csv-channel", default="HEADING", help="the channel --csv writes (default %(default)s)")
    ap.add_argument("--count", type=int, default=0, help="exit after this many messages printed (0: no limit)")
    ap.add_argument("--duration", type=float, default=0.0, help="exit after this many seconds (0: no limit)")
    ap.add_argument("--types", metavar="DIR", help="folder with the generated `headingd` Python package "
                    "(default $HEADINGD_LCM_PYTHON, else this checkout's build*/daemon/lcmgen/python, "
                    "else the installed package)")
    args = ap.parse_args()

    try:
        group, port, _ = parse_url(args.url)
        types = load_types(find_types_dir(args.types))
    except (ValueError, ImportError) as e:
        print(f"headingd_listen: {e}", file=sys.stderr)
        return 2
    wanted = None if args.channels.strip() == "*" else {c.strip() for c in args.channels.split(",") if c.strip()}
    sock = open_socket(group, port)
    reassembler = Reassembler()
    unknown_types = 0
    printed = 0
    csv_file = open(args.csv, "w", newline="", encoding="utf-8") if args.csv else None
    csv_writer = None
    deadline = time.monotonic() + args.duration if args.duration > 0 else None
    try:
        while (deadline is None or time.monotonic() < deadline) and (args.count == 0 or printed < args.count):
            try:
                datagram, sender = sock.recvfrom(65536)
            except socket.timeout:
                reassembler.expire(time.monotonic())
                continue
            message = reassembler.add(datagram, sender, time.monotonic())
            if message is None:
                continue
            channel, payload = message
            if wanted is not None and channel not in wanted and channel != args.csv_channel:
                continue
            cls = types.get(payload[:8])
            if cls is None:
                unknown_types += 1
                continue
            fields = plain(cls.decode(payload))
            if csv_file is not None and channel == args.csv_channel:
                if csv_writer is None:
                    csv_writer = csv.DictWriter(csv_file, fieldnames=list(fields))
                    csv_writer.writeheader()
                csv_writer.writerow({k: json.dumps(v) if isinstance(v, (list, dict)) else ("" if v is None else v)
                                     for k, v in fields.items()})
                csv_file.flush()
            if wanted is None or channel in wanted:
                print(json.dumps({"channel": channel, "type": cls.__name__, **fields}), flush=True)
                printed += 1
    except KeyboardInterrupt:
        pass
    finally:
        if csv_file is not None:
            csv_file.close()
        counts = reassembler.counts
        print(f"headingd_listen: {counts['datagrams']} datagrams, {printed} messages printed, "
              f"{counts['not_lcm']} not LCM, {counts['fragments_lost']} fragmented messages incomplete, "
              f"{unknown_types} of unknown types", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
