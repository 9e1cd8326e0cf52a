#!/usr/bin/env python3
"""The tail of a `solve --batch` run: what its per-problem times (time_s) cost on T
threads when scheduled as solve_all schedules them (problems started in input order,
at most 4 T + 4 held between the first unwritten one and the last started) against
the same schedule with no limit on what is held (a slow problem then never stops the
others) and against perfect balance (the sum over T).

  bench/batch_tail.py OUT.jsonl THREADS [MEASURED_WALL_S]
"""
import heapq
import json
import sys


def schedule(times, threads, window=None):
    """Makespan of starting the problems in order on the earliest free thread; with a
    window, problem i may start only once problems 0 .. i - window have finished (the
    writer has let them go)."""
    free = [0.0] * threads
    heapq.heapify(free)
    finish = []
    # Finish time of the prefix 0..i (the writer writes in order).
    prefix_done = []
    for i, t in enumerate(times):
        start = heapq.heappop(free)
        if window is not None and i >= window:
            start = max(start, prefix_done[i - window])
        end = start + t
        finish.append(end)
        prefix_done.append(max(end, prefix_done[-1]) if prefix_done else end)
        heapq.heappush(free, end)
    return max(finish) if finish else 0.0


def main():
    path, threads = sys.argv[1], int(sys.argv[2])
    measured = float(sys.argv[3]) if len(sys.argv) > 3 else None
    times = []
    with open(path) as f:
        for line in f:
            if line.strip():
                times.append(float(json.loads(line).get("time_s", 0.0)))
    balanced = sum(times) / threads
    unbounded = schedule(times, threads)
    held = schedule(times, threads, 4 * threads + 4)
    slowest = max(times) if times else 0.0
    print(f"  tail on {threads} threads, {len(times)} problems (slowest {slowest:.3f} s, "
          f"sum {sum(times):.3f} s): perfect balance {balanced:.3f} s, in order with no hold "
          f"{unbounded:.3f} s, with the writer's hold of {4 * threads + 4} problems {held:.3f} s"
          + (f", measured {measured:.3f} s" if measured is not None else ""))
    print(f"  the ordered writer's hold costs {100 * (held / unbounded - 1):.1f} %; the end "
          f"of the batch (threads idle while the last problems finish) "
          f"{100 * (unbounded / balanced - 1):.1f} % over perfect balance")


if __name__ == "__main__":
    main()
