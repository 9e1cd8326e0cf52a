#!/usr/bin/env python3
"""Fits the recorded carom shots with each cushion model and compares them shot by shot.

    python3 bench/fit_models.py build/apps/cueplan/cueplan ../shared/data/carom_tracks/train.jsonl

Runs `cueplan fit --json` once per physics file (docs/fit/carom_calibrated.yaml: Mathavan
2010 with the calibrated carom constants; docs/fit/carom_han_2005.yaml: the same constants
with the Han 2005 cushion; docs/fit/carom_stronge.yaml: with the stronge_compliant
cushion) and prints each model's cue-ball RMSE distribution and how many
shots each fits better. Works with any python3 (standard library only).
"""
import json
import statistics
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
MODELS = {
    "mathavan_2010": ROOT / "docs/fit/carom_calibrated.yaml",
    "han_2005": ROOT / "docs/fit/carom_han_2005.yaml",
    "stronge_compliant": ROOT / "docs/fit/carom_stronge.yaml",
}


def fit(cueplan, tracks, physics):
    out = subprocess.run([cueplan, "fit", tracks, "--json", "--physics", str(physics)],
                         check=True, capture_output=True, text=True).stdout
    return {j["id"]: 100.0 * j["rmse_cue_m"] for j in map(json.loads, out.splitlines())}


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    cueplan, tracks = sys.argv[1], sys.argv[2]
    rmse = {name: fit(cueplan, tracks, physics) for name, physics in MODELS.items()}
    for name, by_id in rmse.items():
        v = sorted(by_id.values())
        p90 = v[max(0, int(round(0.9 * len(v))) - 1)]
        print(f"{name:14s} shots {len(v)}  median {statistics.median(v):.2f} cm  "
              f"90th percentile {p90:.2f} cm  mean {statistics.mean(v):.2f} cm")
    a = rmse["mathavan_2010"]
    for other in ("han_2005", "stronge_compliant"):
        b = rmse[other]
        ids = sorted(set(a) & set(b))
        print(f"{other} closer than mathavan_2010 by more than 0.5 cm on "
              f"{sum(b[i] < a[i] - 0.5 for i in ids)} shots, mathavan_2010 on "
              f"{sum(a[i] < b[i] - 0.5 for i in ids)}, within 0.5 cm on the rest (of {len(ids)})")
    c = rmse["han_2005"]
    s = rmse["stronge_compliant"]
    ids = sorted(set(a) & set(c) & set(s))
    print("shot  mathavan_2010  han_2005  stronge_compliant (cm)")
    for i in ids:
        print(f"{i:4d}  {a[i]:13.2f}  {c[i]:8.2f}  {s[i]:17.2f}")


if __name__ == "__main__":
    main()
