#!/usr/bin/python3
"""Prefixes every line of stdin with the seconds since this filter started, the CPU seconds (user +
system, all threads) the process named in <pidfile> (or, when that is /usr/bin/time, its child) had
used by then, and its peak and current resident memory in kB (VmHWM, VmRSS), read from
/proc/<pid>/stat and /proc/<pid>/status. Used on `urbanvec vectorize -progress lines -timings` output
so that the bench can give wall time, CPU utilisation and memory per stage. Prints
"<wall> <cpu> <peak kB> <resident kB> <line>"; a final "... EOF" line marks the end of the stream
(the process exited or closed stdout).

Usage: <command> | timestamp.py <pidfile>
"""
import os
import sys
import time

TICKS = os.sysconf("SC_CLK_TCK")


def measured_pid(pidfile):
    """The pid in pidfile, or its only child when that process is /usr/bin/time."""
    with open(pidfile) as f:
        pid = int(f.read().strip())
    with open("/proc/%d/comm" % pid) as f:
        if f.read().strip() != "time":
            return pid
    with open("/proc/%d/task/%d/children" % (pid, pid)) as f:
        children = f.read().split()
    if len(children) != 1:
        raise ValueError("no child yet")
    return int(children[0])


def cpu_seconds(pidfile, cache):
    if "pid" not in cache:
        try:
            cache["pid"] = measured_pid(pidfile)
        except (OSError, ValueError):
            return cache.get("cpu", 0.0)
    try:
        with open("/proc/%d/stat" % cache["pid"]) as f:
            fields = f.read().rsplit(")", 1)[1].split()
        # fields[0] is the state (stat field 3): utime and stime are stat fields 14 and 15.
        cache["cpu"] = (int(fields[11]) + int(fields[12])) / TICKS
    except (OSError, IndexError, ValueError):
        pass  # the process has exited: keep the last reading
    try:
        with open("/proc/%d/status" % cache["pid"]) as f:
            for line in f:
                if line.startswith(("VmHWM:", "VmRSS:")):
                    cache[line[:5]] = int(line.split()[1])
    except (OSError, IndexError, ValueError):
        pass
    return cache.get("cpu", 0.0)


def stamp(start, pidfile, cache, text):
    now = time.monotonic() - start
    cpu = cpu_seconds(pidfile, cache)
    return "%.3f %.2f %d %d %s\n" % (now, cpu, cache.get("VmHWM", 0), cache.get("VmRSS", 0), text)


def main():
    if len(sys.argv) != 2:
        sys.stderr.write("Usage: <command> | timestamp.py <pidfile>\n")
        return 2
    pidfile = sys.argv[1]
    start = time.monotonic()
    cache = {}
    out = sys.stdout
    for line in sys.stdin:
        out.write(stamp(start, pidfile, cache, line.rstrip("\n")))
    out.write(stamp(start, pidfile, cache, "EOF"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
