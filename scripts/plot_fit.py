#!/usr/bin/python3
"""Fitted vs target curves of a `dtwire fit` output directory -> <dir>/fit_curves.png.

Usage: scripts/plot_fit.py OUT_DIR
Reads OUT_DIR/parameters.json (fit_quality lists each curve's target and fitted CSV) and draws
one panel per curve and channel: target as points, fit as a line, with the curve's R^2.
"""
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_csv(path):
    with open(path) as f:
        rows = [line for line in f if line.strip() and not line.startswith("#")]
    reader = csv.reader(rows)
    header = next(reader)
    columns = {name: [] for name in header}
    for row in reader:
        for name, cell in zip(header, row):
            columns[name].append(float(cell))
    return columns


def column(columns, quantity):
    for name, values in columns.items():
        if name.rsplit("_", 1)[0] == quantity:
            return name, values
    raise KeyError(quantity)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    with open(os.path.join(out, "parameters.json")) as f:
        fit = json.load(f)
    panels = fit["fit_quality"]
    cols = min(4, len(panels))
    rows = math.ceil(len(panels) / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(3.6 * cols, 2.9 * rows), squeeze=False)
    for ax, q in zip(axes.flat, panels):
        target = read_csv(os.path.join(out, q["target_csv"]))
        fitted = read_csv(os.path.join(out, q["fitted_csv"]))
        x_name, x = column(target, q["abscissa"])
        y_name, y = column(target, q["quantity"])
        _, xf = column(fitted, q["abscissa"])
        _, yf = column(fitted, q["quantity"])
        ax.plot(x, y, ".", ms=3, color="0.5", label="target")
        ax.plot(xf, yf, "-", lw=1.3, color="C3", label="fit")
        ax.set_title("%s  (R$^2$ = %.3f)" % (q["experiment"], q["r_squared"]), fontsize=8)
        ax.set_xlabel(x_name, fontsize=7)
        ax.set_ylabel(y_name, fontsize=7)
        ax.tick_params(labelsize=6)
    for ax in list(axes.flat)[len(panels):]:
        ax.axis("off")
    axes.flat[0].legend(fontsize=7)
    fig.suptitle("%s: %s" % (fit.get("law", ""), fit.get("title", "")), fontsize=9)
    fig.tight_layout()
    target_file = os.path.join(out, "fit_curves.png")
    temporary = target_file + ".tmp.png"
    fig.savefig(temporary, dpi=110)
    os.replace(temporary, target_file)  # atomic, like every dtwire result
    print("wrote", target_file)


if __name__ == "__main__":
    main()
