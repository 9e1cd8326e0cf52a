#!/usr/bin/env python3
"""cueplan.rebound over 10^5 numpy rows against `cueplan rebound --batch` on the same
rows (bench/batch_bench.sh's file: random.Random(19), exact method), on 1 and 2
threads, alternating, several runs each; wall-clock and CPU seconds (the CPU time of
the command's process, or of this process during the call: every thread's), medians.
The outputs are checked equal first (bit for bit: the batch prints the shortest text
that reads back as the same double).

    PYTHONPATH=build/python python3 bench/python_rebound_bench.py [--runs 5] [--rows 100000]
"""
import argparse
import csv
import os
import platform
import random
import resource
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "build", "python"))
import cueplan  # noqa: E402

p = argparse.ArgumentParser()
p.add_argument("--runs", type=int, default=5)
p.add_argument("--rows", type=int, default=100000)
p.add_argument("--binary", default=os.path.join(ROOT, "build", "apps", "cueplan", "cueplan"))
args = p.parse_args()

work = tempfile.mkdtemp()
path = os.path.join(work, "rebounds.csv")
r = random.Random(19)
with open(path, "w") as f:
    f.write("speed,angle_deg,topspin_k,sidespin_k\n")
    for _ in range(args.rows):
        f.write(f"{r.uniform(0.1, 2):.6g},{r.uniform(5, 175):.6g},{r.uniform(-1, 1):.4g},{r.uniform(-1, 1):.4g}\n")
rows = np.loadtxt(path, delimiter=",", skiprows=1)
cols = [np.ascontiguousarray(rows[:, k]) for k in range(4)]
out = os.path.join(work, "out.csv")


def command(threads):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    started = time.perf_counter()
    with open(out, "w") as f:
        subprocess.run([args.binary, "rebound", "--batch", path, "--threads", str(threads)], stdout=f,
                       stderr=subprocess.DEVNULL, check=True)
    wall = time.perf_counter() - started
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def module(threads):
    cpu = time.process_time()
    started = time.perf_counter()
    result = cueplan.rebound(*cols, threads=threads)
    return time.perf_counter() - started, time.process_time() - cpu, result


# The same numbers first.
command(1)
_, _, got = module(1)
with open(out) as f:
    table = list(csv.DictReader(f))
for key in ("rebound_speed", "rebound_angle_deg", "vx", "vy", "wx", "wy", "wz"):
    assert np.array_equal(got[key], np.array([float(t[key]) for t in table])), key
print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores, load average "
      f"{' '.join(open('/proc/loadavg').read().split()[:3])}; {args.rows} rows, outputs equal")
print("| threads | rebound --batch wall (s) | cueplan.rebound wall (s) | wall ratio | batch CPU (s) | "
      "module CPU (s) | CPU ratio |")
print("|---|---|---|---|---|---|---|")
for threads in (1, 2):
    cw, cc, mw, mc = [], [], [], []
    for _ in range(args.runs):
        w, c = command(threads)
        cw.append(w)
        cc.append(c)
        w, c, _ = module(threads)
        mw.append(w)
        mc.append(c)
    m = statistics.median
    print(f"| {threads} | {m(cw):.3f} | {m(mw):.3f} | {m(mw) / m(cw):.2f} | {m(cc):.3f} | {m(mc):.3f} | "
          f"{m(mc) / m(cc):.2f} |")
