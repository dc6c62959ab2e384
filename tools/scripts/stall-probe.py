#!/usr/bin/env python3
"""Measures when this machine cannot run even its most urgent thread: one process per CPU,
pinned there, under SCHED_FIFO 99, sleeps 1 ms at a time and writes down every wake that
comes later than THRESHOLD_MS. Nothing inside a program can run while such a stall lasts
(on a virtual machine: the host not running the virtual CPU), so a daemon's late tick in
the same moment is the machine's doing, not the daemon's. soak.sh runs it beside headingd.

usage: stall-probe.py OUT.csv [THRESHOLD_MS]      (default 2 ms; runs until SIGTERM/SIGINT)
OUT.csv: wall_utime_us,cpu,late_ms (the wall clock of the late wake, as LCM's utime).
Without the right to SCHED_FIFO (not root, no CAP_SYS_NICE) it says so on stderr, writes
`# not real-time` as the first line, and measures at normal priority.
"""
import ctypes
import os
import signal
import sys
import time

PERIOD_S = 0.001


def probe(cpu, out_path, threshold_s, realtime):
    os.sched_setaffinity(0, {cpu})
    if realtime:
        os.sched_setscheduler(0, os.SCHED_FIFO, os.sched_param(99))
    with open(out_path, "a", buffering=1) as out:
        while True:
            before = time.monotonic()
            time.sleep(PERIOD_S)
            late = time.monotonic() - before - PERIOD_S
            if late > threshold_s:
                out.write(f"{time.time_ns() // 1000},{cpu},{late * 1e3:.3f}\n")


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    out_path = sys.argv[1]
    threshold_s = float(sys.argv[2]) / 1e3 if len(sys.argv) == 3 else 0.002
    realtime = True
    try:
        os.sched_setscheduler(0, os.SCHED_FIFO, os.sched_param(99))
        os.sched_setscheduler(0, os.SCHED_OTHER, os.sched_param(0))
    except PermissionError as e:
        realtime = False
        print(f"stall-probe: SCHED_FIFO refused ({e}); measuring at normal priority", file=sys.stderr)
    with open(out_path, "w") as out:
        if not realtime:
            out.write("# not real-time\n")
        out.write("wall_utime_us,cpu,late_ms\n")
    children = []
    for cpu in sorted(os.sched_getaffinity(0)):
        pid = os.fork()
        if pid == 0:
            signal.signal(signal.SIGTERM, signal.SIG_DFL)
            signal.signal(signal.SIGINT, signal.SIG_DFL)
            # A real-time busy loop must not outlive its parent: PR_SET_PDEATHSIG (1).
            ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGKILL)
            if os.getppid() == 1:
                os._exit(0)
            try:
                probe(cpu, out_path, threshold_s, realtime)
            finally:
                os._exit(0)
        children.append(pid)

    def stop(signum, frame):
        for pid in children:
            os.kill(pid, signal.SIGTERM)
        for pid in children:
            os.waitpid(pid, 0)
        sys.exit(0)

    signal.signal(signal.SIGTERM, stop)
    signal.signal(signal.SIGINT, stop)
    while True:
        signal.pause()


if __name__ == "__main__":
    main()
