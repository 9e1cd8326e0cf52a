#!/usr/bin/env python3
"""Summarises `cueplan fit --json` outputs: the cue-ball RMSE distribution, the fitted
strokes at the miscue limit, the fit time per shot; with two files, shot by shot.

    cueplan fit train.jsonl --physics docs/fit/carom_calibrated.yaml --json > a.jsonl
    python3 bench/fit_stats.py a.jsonl [b.jsonl]

Quantiles interpolate linearly between ranks (as `cueplan calibrate` reports them).
Standard library only.
"""
import json
import math
import sys


def quantile(values, q):
    v = sorted(values)
    pos = q * (len(v) - 1)
    i = int(pos)
    f = pos - i
    return v[i] * (1 - f) + v[min(i + 1, len(v) - 1)] * f


def load(path):
    with open(path) as f:
        return {str(j["id"]): j for j in map(json.loads, filter(str.strip, f))}


def summary(name, fits):
    e = [100.0 * j["rmse_cue_m"] for j in fits.values()]
    spin = [math.hypot(j["shot"]["topspin_k"], j["shot"]["sidespin_k"]) for j in fits.values()]
    secs = [j["shot"].get("fit_seconds", float("nan")) for j in fits.values()]
    print(f"{name}: {len(e)} shots; cue-ball RMSE median {quantile(e, 0.5):.2f} cm, "
          f"90th percentile {quantile(e, 0.9):.2f} cm, mean {sum(e) / len(e):.2f} cm; "
          f"<= 6 cm: {sum(x <= 6 for x in e)}, <= 15 cm: {sum(x <= 15 for x in e)}")
    print(f"  quantiles 10/25/50/75/90 %: " +
          " ".join(f"{quantile(e, q):.1f}" for q in (0.1, 0.25, 0.5, 0.75, 0.9)) +
          f", max {max(e):.1f} cm")
    print(f"  strokes at the miscue limit (sqrt(k_T^2 + k_S^2) >= 1.249): "
          f"{sum(s >= 1.249 for s in spin)}; |k_T| > 1: "
          f"{sum(abs(j['shot']['topspin_k']) > 1 for j in fits.values())}, |k_S| > 1: "
          f"{sum(abs(j['shot']['sidespin_k']) > 1 for j in fits.values())}")
    print(f"  fit wall time per shot: median {quantile(secs, 0.5):.2f} s, max {max(secs):.2f} s")


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    runs = [(p, load(p)) for p in sys.argv[1:]]
    for name, fits in runs:
        summary(name, fits)
    if len(runs) == 2:
        (na, a), (nb, b) = runs
        ids = sorted(set(a) & set(b), key=lambda s: (len(s), s))
        d = {i: 100.0 * (b[i]["rmse_cue_m"] - a[i]["rmse_cue_m"]) for i in ids}
        print(f"second closer by more than 0.5 cm on {sum(x < -0.5 for x in d.values())} shots, "
              f"first on {sum(x > 0.5 for x in d.values())}, within 0.5 cm on the rest "
              f"(of {len(ids)})")
        print("shot  first  second (cm)")
        for i in ids:
            print(f"{i:>4}  {100 * a[i]['rmse_cue_m']:5.2f}  {100 * b[i]['rmse_cue_m']:6.2f}")


if __name__ == "__main__":
    main()
