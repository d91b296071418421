#!/usr/bin/env python3
"""Plot one channel against another for one or more dtwire curve CSV files.

usage: plot_curves.py OUT.png X_QUANTITY Y_QUANTITY TITLE CSV [CSV ...]

Columns are matched by quantity (the column name without its unit), e.g. `displacement` and
`force` match displacement_mm and force_N; axis labels show the unit of the first file.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_curve(path):
    metadata, rows, header = {}, [], None
    with open(path, newline="") as handle:
        for line in handle:
            text = line.strip()
            if not text:
                continue
            if text.startswith("#"):
                key, sep, value = text[1:].partition(":")
                if sep and header is None:
                    metadata[key.strip()] = value.strip()
                continue
            cells = next(csv.reader([text]))
            if header is None:
                header = cells
            else:
                rows.append([float(c) for c in cells])
    return metadata, header, rows


def column(header, quantity, path):
    for index, name in enumerate(header):
        if name.rsplit("_", 1)[0] == quantity:
            return index, name.rsplit("_", 1)[1]
    sys.exit(f"{path}: no column for quantity '{quantity}' (columns: {', '.join(header)})")


def main():
    if len(sys.argv) < 6:
        sys.exit(__doc__)
    out, x_quantity, y_quantity, title, files = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], sys.argv[5:]
    figure, axes = plt.subplots(figsize=(7, 4.5))
    units = None
    for path in files:
        metadata, header, rows = read_curve(path)
        xi, x_unit = column(header, x_quantity, path)
        yi, y_unit = column(header, y_quantity, path)
        units = units or (x_unit, y_unit)
        label = metadata.get("label") or metadata.get("source") or path.rsplit("/", 1)[-1]
        axes.plot([r[xi] for r in rows], [r[yi] for r in rows], label=label, linewidth=1.5)
    axes.set_xlabel(f"{x_quantity.replace('_', ' ')} ({units[0]})")
    axes.set_ylabel(f"{y_quantity.replace('_', ' ')} ({units[1]})")
    axes.set_title(title)
    axes.grid(True, alpha=0.3)
    axes.legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(out, dpi=120)


if __name__ == "__main__":
    main()
