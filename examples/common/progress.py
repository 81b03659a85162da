#!/usr/bin/env python3
"""Print a progress line every few seconds while a LAMMPS run writes its log.

    progress.py LOG --name NAME [--every 5] [--pid PID]

Reads the log as it grows: the simulated end time from the deck's
'fix ... halt 1 v_t >= TEND' line (as LAMMPS echoes it, variables
substituted), or the step count of the last 'run N' line; the thermo rows
(the header holds 'Step' and 'Time'). Prints, every --every seconds of wall
time,

    [NAME] t = 31.0 of 90.0 us (34 %), step 880, 61 steps/s, about 97 s left

and stops when the log has 'Total wall time', when the process --pid ends,
or after --timeout seconds. Standard library only; never fails the run it
watches (every parsing problem is a line skipped).
"""
import argparse
import os
import re
import sys
import time

HALT = re.compile(r"^\s*fix\s+\S+\s+\S+\s+halt\s+\d+\s+v_t\s*>=\s*([-+0-9.eE]+)")
RUN = re.compile(r"^\s*run\s+(\d+)\s*$")


class LogState:
    """What the log has shown so far."""

    def __init__(self):
        self.tend = None       # simulated end time [s]
        self.nrun = None       # steps of the last 'run N'
        self.cols = None       # thermo header
        self.step = None
        self.time = None
        self.done = False

    def line(self, text):
        m = HALT.match(text)
        if m:
            try:
                self.tend = float(m.group(1))
            except ValueError:
                pass
            return
        m = RUN.match(text)
        if m:
            self.nrun = int(m.group(1))
            return
        words = text.split()
        if not words:
            return
        if words[0] == "Step":
            self.cols = words
            return
        if text.startswith("Total wall time"):
            self.done = True
            return
        if self.cols and len(words) == len(self.cols) and words[0].isdigit():
            try:
                self.step = int(words[0])
                if "Time" in self.cols:
                    self.time = float(words[self.cols.index("Time")])
            except ValueError:
                pass
        elif self.cols and words[0] == "Loop":
            self.cols = None


def fmt_time(s):
    if s is None:
        return "?"
    if s < 120:
        return "%.0f s" % s
    return "%.1f min" % (s / 60.0)


def alive(pid):
    if pid is None:
        return True
    try:
        os.kill(pid, 0)
    except OSError:
        return False
    return True


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("log")
    ap.add_argument("--name", default="run")
    ap.add_argument("--every", type=float, default=5.0)
    ap.add_argument("--pid", type=int)
    ap.add_argument("--timeout", type=float, default=24 * 3600.0)
    a = ap.parse_args()

    st = LogState()
    pos = 0
    start = time.time()
    obs = []             # (wall, step, time) whenever a new thermo row arrived
    buf = ""
    while time.time() - start < a.timeout:
        time.sleep(a.every)
        try:
            with open(a.log, errors="replace") as f:
                f.seek(pos)
                chunk = f.read()
                pos = f.tell()
        except OSError:
            chunk = ""
        buf += chunk
        *lines, buf = buf.split("\n")
        for ln in lines:
            st.line(ln)
        if st.done or not alive(a.pid):
            break
        now = time.time()
        if st.step is None:
            print("[%s] setting up (%s)" % (a.name, fmt_time(now - start)), flush=True)
            continue
        if not obs or st.step != obs[-1][1]:
            obs.append((now, st.step, st.time if st.time is not None else 0.0))
        # rates over the observations of the last minute (at least two)
        recent = [o for o in obs if now - o[0] <= 60.0]
        first = recent[0] if len(recent) >= 2 else (obs[-2] if len(obs) >= 2 else None)
        rate = left = frac = None
        if first is not None and obs[-1][0] > first[0] and obs[-1][1] > first[1]:
            w = obs[-1][0] - first[0]
            rate = (obs[-1][1] - first[1]) / w
            if st.tend and obs[-1][2] > first[2]:
                left = (st.tend - obs[-1][2]) / ((obs[-1][2] - first[2]) / w)
            elif st.nrun:
                left = (st.nrun - obs[-1][1]) / rate
            if left is not None:
                left -= now - obs[-1][0]
        if st.tend and st.time is not None:
            frac = st.time / st.tend
        elif st.nrun:
            frac = st.step / float(st.nrun)
        head = "[%s]" % a.name
        if st.time is not None and st.tend:
            head += " t = %.1f of %.1f us" % (st.time * 1e6, st.tend * 1e6)
        elif st.time is not None:
            head += " t = %.1f us" % (st.time * 1e6)
        if frac is not None:
            head += " (%.0f %%)" % (100 * min(frac, 1.0))
        parts = [head, "step %d" % st.step]
        if rate:
            parts.append("%.0f steps/s" % rate)
        if left is not None:
            parts.append("about %s left" % fmt_time(max(left, 0.0)))
        print(", ".join(parts), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
