#!/usr/bin/env python3
"""Punch curves (platter force against travel) of one or more `dtwire dem run` curve.csv files,
with the thesis's DEM punch figures (Previtali: loading from 0.20 m, peak 25 kN at 0.53 m) as
markers.

usage: plot_punch.py OUT.png CSV [CSV ...]

Each curve is labelled by its `# label:` line (`dem run --label`, else the run's title) and
marked at its own peak; the legend sits below the axes so that it hides no curve.
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from plot_curves import read_curve as read_curve_columns  # noqa: E402  (same folder)

THESIS_ONSET_M = 0.20
THESIS_PEAK_KN = 25.0
THESIS_PEAK_M = 0.53
ONSET_FORCE_KN = 1.0  # the onset of dem run's summary: force first at 1 kN


def read_curve(path):
    metadata, header, values = read_curve_columns(path)
    for needed in ("tool_displacement_mm", "tool_force_N"):
        if header is None or needed not in header:
            sys.exit(f"{path}: no column {needed} (a dem run punch curve.csv is expected)")
    return metadata, [dict(zip(header, row)) for row in values]


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    out, files = sys.argv[1], sys.argv[2:]
    figure, axes = plt.subplots(figsize=(7, 5.2))
    for path in files:
        metadata, rows = read_curve(path)
        x = [r["tool_displacement_mm"] / 1000.0 for r in rows]
        f = [r["tool_force_N"] / 1000.0 for r in rows]
        peak = max(range(len(f)), key=f.__getitem__)
        label = metadata.get("label") or path.rsplit("/", 1)[-1]
        (line,) = axes.plot(x, f, linewidth=1.5, label=f"{label}: {f[peak]:.1f} kN at {x[peak]:.2f} m")
        axes.plot([x[peak]], [f[peak]], "o", color=line.get_color(), markersize=5)
    axes.plot([THESIS_PEAK_M], [THESIS_PEAK_KN], "k*", markersize=13,
              label=f"thesis DEM punch peak: {THESIS_PEAK_KN:.0f} kN at {THESIS_PEAK_M:.2f} m")
    axes.plot([THESIS_ONSET_M], [ONSET_FORCE_KN], "kv", markersize=9,
              label=f"thesis onset: {THESIS_ONSET_M:.2f} m (force at {ONSET_FORCE_KN:.0f} kN)")
    axes.set_xlabel("platter travel (m)")
    axes.set_ylabel("platter force (kN)")
    axes.set_title("Punch test, 3 x 3 m panel of 8x10 / 2.7 mm mesh")
    axes.set_xlim(left=0.0)
    axes.set_ylim(bottom=0.0)
    axes.grid(True, alpha=0.3)
    axes.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=1, frameon=False)
    figure.tight_layout()
    figure.savefig(out, dpi=120, bbox_inches="tight")


if __name__ == "__main__":
    main()
