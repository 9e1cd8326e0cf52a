#!/usr/bin/env python3
"""How stable is `cueplan solve`'s advice across seeds?

For every shipped problem (problems/*.yaml, problems/pots/*.yaml) solves with seeds
1..N on one thread and reports, per problem, how many seeds recommend the most common
family (route, draw/stun/follow, side or none) and the range of P(both) of the answers.
A problem counts as stable when at least 90 % of the seeds agree (issue: "the
recommended stroke's family is the same on >= 90 % of shipped problems").

    python3 bench/seed_stability.py build/apps/cueplan/cueplan [--seeds 10]

Works with any python3 (standard library only).
"""
import argparse
import glob
import json
import subprocess
import sys
from collections import Counter


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("cueplan", help="path of the cueplan program")
    ap.add_argument("--seeds", type=int, default=10)
    ap.add_argument("--problems", nargs="*",
                    default=sorted(glob.glob("problems/*.yaml") + glob.glob("problems/pots/*.yaml")))
    args = ap.parse_args()
    stable = 0
    for path in args.problems:
        fams, ps = [], []
        for seed in range(1, args.seeds + 1):
            run = subprocess.run([args.cueplan, "solve", path, "--seed", str(seed), "--json",
                                  "--threads", "1"], capture_output=True, text=True)
            try:
                d = json.loads(run.stdout)
            except json.JSONDecodeError:
                fams.append("(no answer)")
                continue
            fams.append(d.get("family", "?") if d.get("status") == "solved" else d.get("status"))
            ps.append(d.get("success", {}).get("both", {}).get("p", 0.0))
        family, count = Counter(fams).most_common(1)[0]
        ok = count >= 0.9 * args.seeds
        stable += ok
        print(f"{path:45s} {count:2d}/{args.seeds} {'stable  ' if ok else 'unstable'} "
              f"P(both) {min(ps, default=0):.3f}-{max(ps, default=0):.3f}  {family}", flush=True)
    print(f"stable: {stable} of {len(args.problems)} problems")
    return 0


if __name__ == "__main__":
    sys.exit(main())
