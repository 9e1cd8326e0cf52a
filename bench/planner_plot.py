#!/usr/bin/env python3
"""Planner benchmark tables and a plot of success rate against time budget.

    build/bench/bench_planner --out planner.json
    python3 bench/planner_plot.py planner.json --svg bench/planner_success_vs_budget.svg

Prints Markdown tables (every global x local pairing at each evaluation budget, and
success against the search's time budget) from bench_planner's JSON output, and
draws success rate against time budget (log scale), one line per pairing.
Standard library only.
"""
import argparse
import json
import math
import sys


def pairing_tables(data):
    out = []
    budgets = sorted({p["max_evaluations"] for p in data["pairings"]}, reverse=True)
    for budget in budgets:
        rows = [p for p in data["pairings"] if p["max_evaluations"] == budget]
        out.append(f"max_evaluations = {budget}:\n")
        out.append("| global | local | success | shipped | generated | median | p95 | plans/s |"
                   " mean simulations | solutions per solved plan | no solution found | budget exhausted |")
        out.append("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
        for p in rows:
            out.append(f"| {p['global']} | {p['local']} | {100 * p['success']:.1f} % |"
                       f" {100 * p['success_shipped']:.1f} % | {100 * p['success_generated']:.1f} % |"
                       f" {p['median_ms']:.2f} ms | {p['p95_ms']:.2f} ms | {p['plans_per_s']:.0f} |"
                       f" {p['mean_evaluations']:.0f} | {p['mean_families']:.1f} |"
                       f" {p.get('no_solution_found', p.get('unreachable'))} | {p['budget_exhausted']} |")
        out.append("")
    return "\n".join(out)


def curves(data):
    lines = {}
    for b in data["budgets"]:
        lines.setdefault(f"{b['global']} + {b['local']}", []).append(b)
    for pts in lines.values():
        pts.sort(key=lambda b: b["budget_s"])
    return lines


def budget_table(data):
    lines = curves(data)
    if not lines:
        return ""
    budgets = sorted({b["budget_s"] for b in data["budgets"]})
    out = ["| pairing | " + " | ".join(f"{1e3 * t:g} ms" for t in budgets) + " |",
           "|---|" + "---:|" * len(budgets)]
    for name, pts in lines.items():
        by = {b["budget_s"]: b for b in pts}
        cells = [f"{100 * by[t]['success']:.1f} %" if t in by else "-" for t in budgets]
        out.append(f"| {name} | " + " | ".join(cells) + " |")
    return "\n".join(out)


def svg(data, path):
    lines = curves(data)
    w, h, left, right, top, bottom = 760, 460, 70, 190, 30, 60
    xs = [math.log10(b["budget_s"] * 1e3) for b in data["budgets"]]
    x0, x1 = math.floor(min(xs)), math.ceil(max(xs))
    if x1 == x0:
        x1 += 1

    def px(x):
        return left + (x - x0) / (x1 - x0) * (w - left - right)

    def py(y):  # success rate, 0..1
        return h - bottom - y * (h - top - bottom)

    palette = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2",
               "#7f7f7f"]
    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" '
             'font-family="sans-serif" font-size="12">',
             f'<rect width="{w}" height="{h}" fill="white"/>']
    for e in range(x0, x1 + 1):
        for m in (1, 2, 5):
            v = math.log10(m) + e
            if v > x1:
                continue
            parts.append(f'<line x1="{px(v):.1f}" y1="{top}" x2="{px(v):.1f}" y2="{h - bottom}" '
                         'stroke="#ddd"/>')
            parts.append(f'<text x="{px(v):.1f}" y="{h - bottom + 18}" text-anchor="middle">'
                         f'{m * 10 ** e:g}</text>')
    for k in range(0, 11, 2):
        y = k / 10
        parts.append(f'<line x1="{left}" y1="{py(y):.1f}" x2="{w - right}" y2="{py(y):.1f}" '
                     'stroke="#ddd"/>')
        parts.append(f'<text x="{left - 8}" y="{py(y) + 4:.1f}" text-anchor="end">{k * 10} %</text>')
    parts.append(f'<rect x="{left}" y="{top}" width="{w - left - right}" '
                 f'height="{h - top - bottom}" fill="none" stroke="black"/>')
    parts.append(f'<text x="{(left + w - right) / 2}" y="{h - 15}" text-anchor="middle">'
                 'search time budget max_time_s (ms, log scale)</text>')
    parts.append(f'<text transform="translate(18,{(top + h - bottom) / 2}) rotate(-90)" '
                 'text-anchor="middle">problems solved</text>')
    for i, (name, pts) in enumerate(lines.items()):
        colour = palette[i % len(palette)]
        d = " ".join(f"{px(math.log10(b['budget_s'] * 1e3)):.1f},{py(b['success']):.1f}" for b in pts)
        parts.append(f'<polyline points="{d}" fill="none" stroke="{colour}" stroke-width="1.5"/>')
        for b in pts:
            parts.append(f'<circle cx="{px(math.log10(b["budget_s"] * 1e3)):.1f}" '
                         f'cy="{py(b["success"]):.1f}" r="3" fill="{colour}"/>')
        ly = top + 14 + 18 * i
        parts.append(f'<line x1="{w - right + 12}" y1="{ly - 4}" x2="{w - right + 32}" '
                     f'y2="{ly - 4}" stroke="{colour}" stroke-width="2"/>')
        parts.append(f'<text x="{w - right + 38}" y="{ly}">{name}</text>')
    parts.append("</svg>")
    with open(path, "w") as f:
        f.write("\n".join(parts) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("json", help="bench_planner --out output")
    ap.add_argument("--svg", help="write the success-against-budget plot here")
    args = ap.parse_args()
    with open(args.json) as f:
        data = json.load(f)
    if not data.get("pairings") and not data.get("budgets"):
        sys.exit("planner_plot: no results in " + args.json)
    print(pairing_tables(data))
    print(budget_table(data))
    if args.svg and data.get("budgets"):
        svg(data, args.svg)


if __name__ == "__main__":
    main()
