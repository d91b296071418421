#!/usr/bin/env python3
"""Plot the band of a curve from `dtwire dem propagate`'s band_curve.csv.

usage: plot_band.py OUT.png BAND_CSV TITLE

The first column is the abscissa; the others are <quantity>_fitted, _q05, _q50 and _q95 of one
quantity (the fitted set's curve and the pointwise 5, 50 and 95 % quantiles of the sampled sets).
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    metadata, header, rows = {}, None, []
    with open(path, newline="") as handle:
        for line in handle:
            text = line.strip()
            if not text:
                continue
            if text.startswith("#"):
                key, sep, value = text[1:].partition(":")
                if sep:
                    metadata[key.strip()] = value.strip()
                continue
            cells = next(csv.reader([text]))
            if header is None:
                header = cells
            else:
                rows.append([float(c) if c not in ("", "nan") else float("nan") for c in cells])
    return metadata, header, rows


# The curve CSV's unit symbols that read better spelled out.
UNIT_LABELS = {"Npm": "N/m", "1": "-"}


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    out, path, title = sys.argv[1:]
    metadata, header, rows = read(path)
    column = {name: k for k, name in enumerate(header)}

    def series(suffix):
        for name, k in column.items():
            if f"_{suffix}_" in name:
                return name, [r[k] for r in rows]
        sys.exit(f"{path}: no {suffix} column (columns: {', '.join(header)})")

    x_name = header[0]
    x = [r[0] for r in rows]
    y_name, fitted = series("fitted")
    _, q05 = series("q05")
    _, q50 = series("q50")
    _, q95 = series("q95")
    quantity, unit = y_name.split("_fitted_")
    figure, axes = plt.subplots(figsize=(7, 4.5))
    axes.fill_between(x, q05, q95, alpha=0.3, label=f"5-95 % of {metadata.get('sets', '?')} sampled sets")
    axes.plot(x, q50, linestyle="--", linewidth=1.2, label="median of the sampled sets")
    axes.plot(x, fitted, linewidth=1.8, label="fitted set")
    x_quantity, _, x_unit = x_name.rpartition("_")
    axes.set_xlabel(f"{x_quantity.replace('_', ' ')} ({UNIT_LABELS.get(x_unit, x_unit)})")
    axes.set_ylabel(f"{quantity.replace('_', ' ')} ({UNIT_LABELS.get(unit, unit)})")
    axes.set_title(title, fontsize=10)
    axes.grid(True, alpha=0.3)
    axes.legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(out, dpi=120)


if __name__ == "__main__":
    main()
