#!/usr/bin/env python3
"""Are the stable answers as good as the old seed-dependent ones? Judged on fresh draws.

For every shipped problem (problems/*.yaml, problems/pots/*.yaml): the OLD program's
answers for seeds 1..10 and the NEW program's answer (seed 1; its answer no longer
depends on the seed) are each re-estimated with the NEW program's `simulate --samples N
--seed S` on the same fresh noise draws, which neither planner saw. Choosing the best
of several noisy estimates flatters the winner; fresh common draws do not. Reports, per
problem, the best old answer's fresh P(both) and the low end of its 95 % Wilson
interval, the mean over the ten old answers, and the new answer's fresh P(both).

    python3 bench/answer_quality.py OLD_CUEPLAN NEW_CUEPLAN [--samples 1000] [--seed 424242]

Works with any python3 (standard library only); two problems at a time.
"""
import argparse
import glob
import json
import math
import subprocess
from concurrent.futures import ThreadPoolExecutor


def solve(program, path, seed):
    run = subprocess.run([program, "solve", path, "--seed", str(seed), "--json", "--threads", "1"],
                         capture_output=True, text=True)
    try:
        d = json.loads(run.stdout)
    except json.JSONDecodeError:
        return None
    if d.get("status") != "solved":
        return None
    s = d["shot"]
    return (s["speed"], s["aim_deg"], s["topspin_k"], s["sidespin_k"], s.get("elevation_deg", 0.0))


def fresh_p(program, path, shot, samples, seed):
    v, a, t, s, e = shot
    run = subprocess.run([program, "simulate", path, "--speed", repr(v), "--aim", repr(a),
                          "--topspin-k", repr(t), "--sidespin-k", repr(s), "--elevation-deg", repr(e),
                          "--samples", str(samples), "--seed", str(seed), "--json"],
                         capture_output=True, text=True, check=True)
    return json.loads(run.stdout)["success"]["both"]["p"]


def wilson_low(p, n, z=1.96):
    centre = p + z * z / (2 * n)
    margin = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    return (centre - margin) / (1 + z * z / n)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--samples", type=int, default=1000)
    ap.add_argument("--seed", type=int, default=424242)
    args = ap.parse_args()
    files = sorted(glob.glob("problems/*.yaml") + glob.glob("problems/pots/*.yaml"))

    def judge(path):
        olds = [solve(args.old, path, seed) for seed in range(1, 11)]
        p_of = {}
        for shot in olds:
            if shot and shot not in p_of:
                p_of[shot] = fresh_p(args.new, path, shot, args.samples, args.seed)
        solved = [p_of[s] for s in olds if s]
        best = max(solved, default=0.0)
        mean = sum(solved) / len(solved) if solved else 0.0
        new_shot = solve(args.new, path, 1)
        new = fresh_p(args.new, path, new_shot, args.samples, args.seed) if new_shot else 0.0
        return path, best, wilson_low(best, args.samples), mean, new

    with ThreadPoolExecutor(2) as pool:
        rows = list(pool.map(judge, files))
    print(f"fresh draws: {args.samples} noisy strokes, seed {args.seed}")
    print("| problem | best old answer | its 95 % low | mean of the 10 old answers | new answer | within the best's interval | at least the old mean |")
    print("|---|---|---|---|---|---|---|")
    within = at_mean = 0
    for path, best, low, mean, new in rows:
        within += new >= low
        at_mean += new >= mean
        print(f"| {path.replace('problems/', '')} | {best:.3f} | {low:.3f} | {mean:.3f} | {new:.3f} | "
              f"{'yes' if new >= low else 'no'} | {'yes' if new >= mean else 'no'} |")
    print(f"within the best old answer's interval: {within}/{len(rows)}; "
          f"at least the old answers' mean: {at_mean}/{len(rows)}")


if __name__ == "__main__":
    main()
