#!/usr/bin/env python3
"""Closeness against plausibility, one point per row of a `drape experiment`
table (its table.csv): ME on the x axis, and in two panels the share of the
shirt inside the body (p) and the edge-length error (L_e). A point further
left is closer to the simulation; lower is more plausible. Written for
graphs/experiments/me_gap.yaml (docs/results.md), usable for any table with
ME, p and L_e columns.

    python3 scripts/figures/tradeoff_scatter.py runs/me_gap/table.csv --out me_gap.svg
"""
import argparse
import csv
import html
import math

PANELS = [("p", "p: shirt inside the body (%)", True), ("L_e", "L_e: edge length error (%)", False)]
W, H, PAD = 420, 320, 56


def scale(lo, hi, a, b, log):
    if log:
        lo, hi = math.log10(lo), math.log10(hi)
    return lambda v: a + (b - a) * ((math.log10(v) if log else v) - lo) / (hi - lo)


def ticks(lo, hi, log):
    if log:
        return [10.0 ** e for e in range(math.floor(math.log10(lo)), math.ceil(math.log10(hi)) + 1)]
    step = 10 ** math.floor(math.log10((hi - lo) / 2))
    return [step * k for k in range(math.ceil(lo / step), math.floor(hi / step) + 1)]


def panel(rows, key, title, log, x0):
    xs = [r["ME"] for r in rows]
    ys = [r[key] for r in rows]
    xlo, xhi = min(xs) - 0.03, max(xs) + 0.15  # room for the labels on the right
    ylo, yhi = (min(ys) / 2, max(ys) * 2) if log else (0.0, max(ys) * 1.15)
    sx = scale(xlo, xhi, x0 + PAD, x0 + W - 12, False)
    sy = scale(ylo, yhi, H - PAD, 30, log)
    out = [f'<text x="{x0 + W / 2}" y="20" font-size="13" text-anchor="middle">{html.escape(title)}</text>',
           f'<rect x="{x0 + PAD}" y="30" width="{W - PAD - 12}" height="{H - PAD - 30}" fill="none" stroke="#999"/>']
    for t in ticks(ylo, yhi, log):
        if ylo <= t <= yhi:
            out.append(f'<text x="{x0 + PAD - 4}" y="{sy(t) + 4:.1f}" font-size="10" text-anchor="end">{t:g}</text>')
    for t in ticks(xlo, xhi, False):
        out.append(f'<text x="{sx(t):.1f}" y="{H - PAD + 14}" font-size="10" text-anchor="middle">{t:g}</text>')
    out.append(f'<text x="{x0 + W / 2}" y="{H - PAD + 32}" font-size="11" text-anchor="middle">ME (cm), test bodies</text>')
    placed = []  # label boxes (x0, x1, y): a label that would overlap one drops a line until it does not
    for r in sorted(rows, key=lambda r: r["ME"]):
        baseline = r["row"].startswith("[")
        colour = "#c0392b" if baseline else "#2c3e50"
        x, y = sx(r["ME"]), sy(r[key])
        out.append(f'<circle cx="{x:.1f}" cy="{y:.1f}" r="4" fill="{colour}"/>')
        lx, ly, width = x + 6, y - 5, 5.6 * len(r["row"])
        while any(a < lx + width and lx < b and abs(ly - c) < 11 for a, b, c in placed):
            ly += 11
        placed.append((lx, lx + width, ly))
        out.append(f'<text x="{lx:.1f}" y="{ly:.1f}" font-size="10" fill="{colour}">{html.escape(r["row"])}</text>')
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("table", help="table.csv of drape experiment")
    ap.add_argument("--out", required=True, help="SVG to write")
    ap.add_argument("--title", default="closeness (ME) against plausibility (p, L_e), one point per row")
    args = ap.parse_args()
    with open(args.table) as f:
        rows = [{"row": r["row"], "ME": float(r["ME"]), "p": max(float(r["p"]), 1e-3), "L_e": float(r["L_e"])}
                for r in csv.DictReader(f) if r["ME"] and r["p"] and r["L_e"]]
    body = [f'<text x="12" y="16" font-size="14" font-weight="bold">{html.escape(args.title)}</text>']
    for i, (key, title, log) in enumerate(PANELS):
        body.append(f'<g transform="translate(0, 26)">')
        body += panel(rows, key, title, log, i * (W + 20))
        body.append("</g>")
    width, height = 2 * W + 20, H + 30
    with open(args.out, "w") as f:
        f.write(f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" font-family="sans-serif">\n'
                '<rect width="100%" height="100%" fill="white"/>\n' + "\n".join(body) + "\n</svg>\n")
    print(f"wrote {args.out}: {len(rows)} rows")


if __name__ == "__main__":
    main()
