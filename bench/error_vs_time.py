#!/usr/bin/env python3
"""Error-versus-run-time table and plot from bench_impact's JSON output.

    build/bench/bench_impact --benchmark_format=json > impact.json
    python3 bench/error_vs_time.py impact.json --svg bench/error_vs_time.svg [--cpu]

Prints a Markdown table (one row per method configuration: the mean time per impact
- the benchmark loop's - and the median of the inputs timed one by one, their ratios
to the paper scheme at N = 5000, errors against the converged reference)
and writes a log-log plot of maximum error against time per impact.
Standard library only.
"""
import argparse
import json
import math
import sys


def load(path, clock="real_time"):
    with open(path) as f:
        data = json.load(f)
    rows = []
    benchmarks = data["benchmarks"]
    # With --benchmark_repetitions, take each benchmark's median; otherwise its one run.
    if any(b.get("aggregate_name") == "median" for b in benchmarks):
        benchmarks = [b for b in benchmarks if b.get("aggregate_name") == "median"]
    else:
        benchmarks = [b for b in benchmarks if b.get("run_type") != "aggregate"]
    for b in benchmarks:
        name = b.get("run_name", b["name"])
        unit = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}[b.get("time_unit", "ns")]
        ns = b[clock] * unit
        if name.startswith("BM_ImpactExact/tol_exp:"):
            label = "exact, tol 1e-" + name.split(":")[1]
        elif name.startswith("BM_ImpactExtrapolation/tol_exp:"):
            label = "extrapolation, tol 1e-" + name.split(":")[1]
        elif name.startswith("BM_ImpactBatch/lanes:"):
            lanes = name.split(":")[1].split("/")[0]
            label = ("exact, batch, widest lanes" if lanes == "0" else
                     "exact, batch, one impact at a time" if lanes == "1" else
                     f"exact, batch, {lanes} lanes")
            # Items are impacts: the time per impact is the iteration's over 4096.
            ns = ns / 4096.0
        elif name.startswith("BM_ImpactPaper/N:"):
            label = "paper, N = " + name.split(":")[1]
        elif name.startswith("BM_ImpactTableStrictFallback"):
            label = "table, fallback at tol 1e-12"
        elif name.startswith("BM_ImpactTable"):
            label = "table"
        elif name.startswith("BM_ImpactRollingTable"):
            label = "table, natural roll (k_T = 1)"
        elif name.startswith("BM_ImpactRollingExact"):
            label = "exact, natural roll (k_T = 1)"
        elif name.startswith("BM_ImpactRollingExtrapolation"):
            label = "extrapolation, natural roll (k_T = 1)"
        elif name.startswith("BM_TableQueryRolling"):
            label = "table query alone, natural roll (k_T = 1)"
        elif name.startswith("BM_TableQuery"):
            label = "table query alone"
        else:
            continue
        rows.append({
            "label": label,
            "ns": ns,
            "max_state": b["max_state_err"],
            "median_state": b["median_state_err"],
            "max_speed": b["max_speed_err"],
            "max_angle": b["max_angle_err_deg"],
            "rhs": b["rhs_per_impact"],
            "median_ns": b.get("median_ns"),
        })
    return data.get("context", {}), rows


def duration(ns):
    if ns is None:
        return "-"
    return f"{ns / 1000:.2f} us" if ns >= 1000 else f"{ns:.0f} ns"


def table(rows):
    paper = next((r for r in rows if r["label"] == "paper, N = 5000"), None)
    out = ["| method | mean per impact | median per impact | paper N=5000 / this: mean |"
           " median | max error (state) | median error (state) | max speed error |"
           " max angle error (deg) | work per impact |",
           "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        # Ratios only within one input set (the natural-roll rows have their own), and
        # not for the table query alone, which leaves the declined impacts unsolved.
        comparable = "natural roll" not in r["label"] and "query alone" not in r["label"]
        ratio = f"{paper['ns'] / r['ns']:.1f}x" if paper and comparable else "-"
        median_ratio = "-"
        if paper and comparable and r["median_ns"] and paper["median_ns"]:
            median_ratio = f"{paper['median_ns'] / r['median_ns']:.1f}x"
        out.append(f"| {r['label']} | {duration(r['ns'])} | {duration(r['median_ns'])} |"
                   f" {ratio} | {median_ratio} | {r['max_state']:.1e} |"
                   f" {r['median_state']:.1e} | {r['max_speed']:.1e} | {r['max_angle']:.1e} |"
                   f" {r['rhs']:.0f} |")
    return "\n".join(out)


def svg(rows, path):
    # One input set per plot: the natural-roll rows and the table query alone are
    # reported in the table only.
    rows = [r for r in rows if "natural roll" not in r["label"] and "query alone" not in r["label"]
            and "batch" not in r["label"]]
    w, h, left, right, top, bottom = 720, 460, 80, 30, 30, 60
    xs = [math.log10(r["ns"]) for r in rows]
    ys = [math.log10(max(r["max_state"], 1e-17)) for r in rows]
    x0, x1 = math.floor(min(xs)), math.ceil(max(xs))
    y0, y1 = math.floor(min(ys)), math.ceil(max(ys))
    if x1 == x0:
        x1 += 1
    if y1 == y0:
        y1 += 1

    def px(x):
        return left + (x - x0) / (x1 - x0) * (w - left - right)

    def py(y):
        return h - bottom - (y - y0) / (y1 - y0) * (h - top - bottom)

    colours = {"exact": "#1f77b4", "extrapolation": "#9467bd", "paper": "#d62728",
               "table": "#2ca02c"}
    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" '
             'font-family="sans-serif" font-size="12">',
             f'<rect width="{w}" height="{h}" fill="white"/>']
    for e in range(x0, x1 + 1):
        parts.append(f'<line x1="{px(e)}" y1="{top}" x2="{px(e)}" y2="{h - bottom}" stroke="#ddd"/>')
        parts.append(f'<text x="{px(e)}" y="{h - bottom + 18}" text-anchor="middle">1e{e} ns</text>')
    for e in range(y0, y1 + 1):
        parts.append(f'<line x1="{left}" y1="{py(e)}" x2="{w - right}" y2="{py(e)}" stroke="#ddd"/>')
        parts.append(f'<text x="{left - 8}" y="{py(e) + 4}" text-anchor="end">1e{e}</text>')
    parts.append(f'<rect x="{left}" y="{top}" width="{w - left - right}" '
                 f'height="{h - top - bottom}" fill="none" stroke="black"/>')
    parts.append(f'<text x="{(left + w - right) / 2}" y="{h - 15}" text-anchor="middle">'
                 'time per impact (ns, log scale)</text>')
    parts.append(f'<text transform="translate(20,{(top + h - bottom) / 2}) rotate(-90)" '
                 'text-anchor="middle">max error of outgoing state / V0 (log scale)</text>')
    for method, colour in colours.items():
        pts = [(px(x), py(y), r) for x, y, r in zip(xs, ys, rows) if r["label"].startswith(method)]
        if len(pts) > 1:
            d = " ".join(f"{x:.1f},{y:.1f}" for x, y, _ in sorted(pts, key=lambda p: p[0]))
            parts.append(f'<polyline points="{d}" fill="none" stroke="{colour}" stroke-width="1.5"/>')
        for k, (x, y, r) in enumerate(pts):
            parts.append(f'<circle cx="{x:.1f}" cy="{y:.1f}" r="4" fill="{colour}"/>')
            # Labels clear of the neighbouring curves: exact's to the left of its points,
            # the table's (two points close together) stacked below them.
            if method == "exact":
                tx, ty, anchor = x - 7, y + 4, "end"
            elif method == "table":
                tx, ty, anchor = x + 7, y + 16 + 14 * k, "start"
            else:
                tx, ty, anchor = x + 7, y - 6, "start"
            parts.append(f'<text x="{tx:.1f}" y="{ty:.1f}" fill="{colour}" '
                         f'text-anchor="{anchor}">{r["label"]}</text>')
    parts.append("</svg>")
    with open(path, "w") as f:
        f.write("\n".join(parts) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("json", help="bench_impact --benchmark_format=json output")
    ap.add_argument("--svg", help="write the plot here")
    ap.add_argument("--cpu", action="store_true",
                    help="use the CPU time of the process instead of wall-clock time (on a "
                         "machine shared with other work)")
    args = ap.parse_args()
    context, rows = load(args.json, "cpu_time" if args.cpu else "real_time")
    if not rows:
        sys.exit("error_vs_time: no impact benchmarks in " + args.json)
    print(f"Machine: {context.get('num_cpus', '?')} CPUs at {context.get('mhz_per_cpu', '?')} MHz, "
          f"build {context.get('library_build_type', '?')}, {context.get('date', '')}, "
          f"{'CPU' if args.cpu else 'wall-clock'} time")
    print()
    print(table(rows))
    if args.svg:
        svg(rows, args.svg)


if __name__ == "__main__":
    main()
