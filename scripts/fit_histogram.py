#!/usr/bin/env python3
"""Histogram (SVG) of per-shot cue-ball RMSE from `cueplan calibrate`'s per-shot lines.

usage: fit_histogram.py CALIBRATE_OUTPUT.txt OUT.svg
Reads the lines after "per shot (cm): id fold before held_out all_shots" and draws the
distributions of the starting-constant and the held-out RMSE side by side (2 cm bins).
"""
import sys

def main():
    rows = []
    seen = False
    for line in open(sys.argv[1]):
        if line.startswith("per shot (cm)"):
            seen = True
            continue
        if seen and line.strip():
            p = line.split()
            rows.append((float(p[2]), float(p[3])))
    series = [("starting constants", "#999999", [r[0] for r in rows]),
              ("calibrated, held out", "#0072b2", [r[1] for r in rows])]
    bin_cm, top_cm = 2.0, 40.0
    nbins = int(top_cm / bin_cm) + 1  # the last bin: >= top
    counts = []
    for _, _, v in series:
        c = [0] * nbins
        for x in v:
            c[min(nbins - 1, int(x / bin_cm))] += 1
        counts.append(c)
    W, H, L, B, T = 760, 360, 50, 50, 40
    cmax = max(max(c) for c in counts)
    pw, ph = W - L - 20, H - B - T
    bw = pw / nbins
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" font-family="sans-serif" font-size="12">',
           f'<rect width="{W}" height="{H}" fill="white"/>',
           f'<text x="{W/2}" y="20" text-anchor="middle" font-weight="bold">Per-shot cue-ball RMSE, {len(rows)} shots (2 cm bins; last bin: 40 cm or more)</text>']
    for s, (name, colour, _) in enumerate(series):
        for i, c in enumerate(counts[s]):
            h = ph * c / cmax
            x = L + i * bw + s * bw / 2
            out.append(f'<rect x="{x:.1f}" y="{T + ph - h:.1f}" width="{bw/2 - 1:.1f}" height="{h:.1f}" fill="{colour}"/>')
        out.append(f'<rect x="{W - 200}" y="{T + 10 + 18*s}" width="12" height="12" fill="{colour}"/>')
        out.append(f'<text x="{W - 183}" y="{T + 21 + 18*s}">{name}</text>')
    for i in range(0, nbins + 1, 5):
        x = L + i * bw
        out.append(f'<line x1="{x:.1f}" y1="{T+ph}" x2="{x:.1f}" y2="{T+ph+5}" stroke="black"/>')
        out.append(f'<text x="{x:.1f}" y="{T+ph+18}" text-anchor="middle">{i*bin_cm:.0f}</text>')
    step = max(1, cmax // 5)
    for c in range(0, cmax + 1, step):
        y = T + ph - ph * c / cmax
        out.append(f'<line x1="{L-5}" y1="{y:.1f}" x2="{L}" y2="{y:.1f}" stroke="black"/>')
        out.append(f'<text x="{L-8}" y="{y+4:.1f}" text-anchor="end">{c}</text>')
    out.append(f'<line x1="{L}" y1="{T+ph}" x2="{L+pw}" y2="{T+ph}" stroke="black"/>')
    out.append(f'<line x1="{L}" y1="{T}" x2="{L}" y2="{T+ph}" stroke="black"/>')
    out.append(f'<text x="{L+pw/2}" y="{H-10}" text-anchor="middle">cue-ball RMSE (cm)</text>')
    out.append(f'<text x="14" y="{T+ph/2}" text-anchor="middle" transform="rotate(-90 14 {T+ph/2})">shots</text>')
    out.append('</svg>')
    open(sys.argv[2], "w").write("\n".join(out) + "\n")

main()
