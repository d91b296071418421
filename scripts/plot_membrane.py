#!/usr/bin/env python3
"""Where a punch's force goes at its peak: the membrane sections of one or more `dtwire dem run`
punches (membrane_at_peak.csv; docs/dem_engine.md, "Where the punch's force goes").

usage: plot_membrane.py OUT.png LABEL=RUN_DIR [LABEL=RUN_DIR ...]

Left: the mean radial tension per metre of circumference against the section's radius (line),
the band between the least and the most loaded eighth, the mesh's nominal strength (50 kN/m,
EN 15381 Annex D) and the mean rim tension the thesis's punch (25 kN at 530 mm) needs at each
run's own rim slope (marker). Right: the net's slope at each radius.
"""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

NOMINAL_STRENGTH_KN_PER_M = 50.0
THESIS_PEAK_N = 25000.0
BAD_INPUT = 2


def fail(message):
    print(message, file=sys.stderr)
    sys.exit(BAD_INPUT)


def read_sections(run):
    path = os.path.join(run, "membrane_at_peak.csv")
    if not os.path.exists(path):
        fail(f"plot_membrane.py: {path}: no such file (a platter run writes it)")
    with open(path, newline="") as handle:
        lines = list(handle)
    metadata = {}
    for line in lines:
        if line.startswith("# ") and ": " in line:
            key, _, value = line[2:].partition(": ")
            metadata[key] = value.strip()
    rows = list(csv.DictReader(line for line in lines if not line.startswith("#")))
    if not rows:
        fail(f"plot_membrane.py: {path}: no sections")
    def column(name):
        try:
            return [float(r[name]) for r in rows]
        except (KeyError, TypeError, ValueError):
            fail(f"plot_membrane.py: {path}: column {name} missing or not a number")

    return {"radius": column("radius_m"), "mean": [v / 1000 for v in column("radial_tension_Npm")],
            "largest": [v / 1000 for v in column("largest_sector_tension_Npm")],
            "smallest": [v / 1000 for v in column("smallest_sector_tension_Npm")], "slope": column("slope_deg"),
            "peak": float(metadata.get("tool_force_at_peak_N", "nan"))}


def main():
    if len(sys.argv) < 3 or any("=" not in spec for spec in sys.argv[2:]):
        fail(__doc__)
    out = sys.argv[1]
    fig, (tension_axes, slope_axes) = plt.subplots(1, 2, figsize=(11, 5.6), gridspec_kw={"width_ratios": [3, 2]})
    for k, spec in enumerate(sys.argv[2:]):
        label, _, run = spec.partition("=")
        s = read_sections(run)
        colour = f"C{k}"
        tension_axes.plot(s["radius"], s["mean"], color=colour, label=f"{label}: mean ({s['peak'] / 1000:.1f} kN peak)")
        tension_axes.fill_between(s["radius"], s["smallest"], s["largest"], color=colour, alpha=0.15,
                                  label=f"{label}: least to most loaded eighth")
        if s["slope"][0] > 0:  # a flat rim carries no vertical force at any tension
            needed = THESIS_PEAK_N / (2 * math.pi * s["radius"][0] * math.tan(math.radians(s["slope"][0]))) / 1000
            tension_axes.plot([s["radius"][0]], [needed], marker="v", color=colour, linestyle="none", markersize=9,
                              label=f"25 kN at this rim slope needs {needed:.1f} kN/m")
        slope_axes.plot(s["radius"], s["slope"], color=colour, label=label)
    tension_axes.axhline(NOMINAL_STRENGTH_KN_PER_M, color="black", linestyle="--", linewidth=1,
                         label="mesh nominal strength 50 kN/m")
    tension_axes.set_xlabel("section radius from the platter axis (m)")
    tension_axes.set_ylabel("radial tension at the peak (kN/m)")
    tension_axes.set_ylim(bottom=0)
    tension_axes.grid(alpha=0.3)
    # Below the axes: the bands fill the plot.
    tension_axes.legend(fontsize=7.5, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=2)
    slope_axes.set_xlabel("section radius from the platter axis (m)")
    slope_axes.set_ylabel("net slope at the peak (deg)")
    slope_axes.set_ylim(bottom=0)
    slope_axes.grid(alpha=0.3)
    slope_axes.legend(fontsize=8, loc="upper right")
    fig.suptitle("Punch at its peak: membrane sections (F = 2 pi r T tan(slope))", fontsize=11)
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    print(out)


if __name__ == "__main__":
    main()
