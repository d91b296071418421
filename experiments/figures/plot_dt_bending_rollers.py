#!/usr/bin/env python3
"""DT three-point bending on rollers: the FE roller force against dem_specimen curves.

Usage: plot_dt_bending_rollers.py FE_CURVE.csv OUT.svg LABEL=DEM_CURVE.csv ...

FE_CURVE: `dtwire run experiments/dt/dt_bending.prm` (tool3_displacement_y_mm, tool3_force_y_N);
DEM curves: `dtwire fit <file with the bending experiment> --synthesize DIR` (the same columns,
written through the fit file's mapping). Prints NRMSE (RMSE / FE range) and R^2 of each DEM
curve at the FE points and draws force (log axis: the DEM forces reach tens of kN) against the
roller's displacement along -y as an SVG, without plotting libraries.
"""
import csv
import math
import sys


def read(path):
    rows = list(csv.DictReader(line for line in open(path) if not line.startswith("#")))
    return ([-float(r["tool3_displacement_y_mm"]) for r in rows], [float(r["tool3_force_y_N"]) for r in rows])


def interpolate(xs, ys, x):
    for i in range(1, len(xs)):
        if xs[i] >= x:
            t = (x - xs[i - 1]) / (xs[i] - xs[i - 1]) if xs[i] > xs[i - 1] else 0.0
            return ys[i - 1] + t * (ys[i] - ys[i - 1])
    return ys[-1]


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    fe_x, fe_f = read(sys.argv[1])
    curves = [("FE (level 0)", fe_x, fe_f)]
    mean = sum(fe_f) / len(fe_f)
    for arg in sys.argv[3:]:
        label, path = arg.split("=", 1)
        x, f = read(path)
        residuals = [interpolate(x, f, a) - b for a, b in zip(fe_x, fe_f)]
        ss = sum(e * e for e in residuals)
        print("%s: NRMSE %.3g, R^2 %.4g" % (label, math.sqrt(ss / len(residuals)) / (max(fe_f) - min(fe_f)),
                                            1.0 - ss / sum((b - mean) ** 2 for b in fe_f)))
        curves.append((label, x, f))
    width, height, left, bottom = 640, 420, 70, 50
    low, high = 1.0, 5.0  # log10 of the force axis [N]

    def point(x, f):
        y = (math.log10(max(f, 10.0 ** low)) - low) / (high - low)
        return "%.1f,%.1f" % (left + x / 8.0 * (width - left - 20), height - bottom - y * (height - bottom - 20))

    colours = ["black", "#1f77b4", "#ff7f0e", "#2ca02c"]
    svg = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" font-family="sans-serif" font-size="12">'
           % (width, height), '<rect width="100%" height="100%" fill="white"/>']
    for decade in range(int(low), int(high) + 1):
        y = point(0, 10.0 ** decade).split(",")[1]
        svg.append('<line x1="%d" x2="%d" y1="%s" y2="%s" stroke="#ddd"/>' % (left, width - 20, y, y))
        svg.append('<text x="%d" y="%s" text-anchor="end">1e%d</text>' % (left - 5, y, decade))
    for mm in range(0, 9):
        x = point(mm, 10.0 ** low).split(",")[0]
        svg.append('<text x="%s" y="%d" text-anchor="middle">%d</text>' % (x, height - bottom + 15, mm))
    svg.append('<text x="%d" y="%d" text-anchor="middle">loading roller displacement along -y (mm)</text>'
               % ((width + left) // 2, height - 12))
    svg.append('<text x="15" y="%d" transform="rotate(-90 15 %d)" text-anchor="middle">roller force (N)</text>'
               % (height // 2, height // 2))
    for k, (label, x, f) in enumerate(curves):
        colour = colours[k % len(colours)]
        svg.append('<polyline fill="none" stroke="%s" stroke-width="2" points="%s"/>'
                   % (colour, " ".join(point(a, b) for a, b in zip(x, f))))
        svg.append('<text x="%d" y="%d" fill="%s">%s</text>' % (left + 10, 35 + 16 * k, colour, label))
    svg.append("</svg>")
    open(sys.argv[2], "w").write("\n".join(svg) + "\n")


if __name__ == "__main__":
    main()
