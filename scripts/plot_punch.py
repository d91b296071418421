#!/usr/bin/env python3
"""Punch curves (platter force against travel) of one or more `dtwire dem run` curve.csv files,
with the thesis's DEM punch figures (Previtali: loading from 0.20 m, peak 25 kN at 0.53 m) as
markers.

usage: plot_punch.py OUT.png CSV [CSV ...]

Each curve is labelled by its `# label:` line (`dem run --label`, else the run's title) and
marked at its own peak; the legend sits below the axes so that it hides no curve. A run that
does not apply to its set-up is not drawn as a result: one whose force never reaches the onset
force (1 kN) or still rises when the platter stops (its largest force in the last 1 % of the
travel: the net has not failed, so its "peak" is no figure of the test; the WirePM sets in the
slack state), or whose net was asked to settle to rest and was still moving when the platter
started (`settled_at_rest` false in the run's summary.json beside its curve.csv). It is named
under the figure as not applicable, by the rule of the campaign report
(app/campaign/report_recommendation.hpp).
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from plot_curves import read_curve as read_curve_columns  # noqa: E402  (same folder)

THESIS_ONSET_M = 0.20
THESIS_PEAK_KN = 25.0
THESIS_PEAK_M = 0.53
ONSET_FORCE_KN = 1.0  # the onset of dem run's summary: force first at 1 kN
TRAVEL_END_SHARE = 0.01  # a peak in the last 1 % of the travel is no peak


def not_applicable(x, f):
    """Why a punch curve (m, kN) does not apply to its set-up, or None."""
    peak = max(range(len(f)), key=f.__getitem__)
    at_peak = f"{f[peak]:.1f} kN at {x[peak]:.2f} m"
    if f[peak] < ONSET_FORCE_KN:
        return f"never carries the onset force of 1 kN ({at_peak})"
    if x[peak] >= (1.0 - TRAVEL_END_SHARE) * max(x):
        return f"no peak within the travel ({at_peak}, still rising when the platter stops)"
    return None


def not_at_rest(curve_path):
    """Why the run beside this curve.csv did not start from rest, or None (no summary.json, or a
    settle of a fixed time)."""
    summary_path = os.path.join(os.path.dirname(curve_path) or ".", "summary.json")
    if not os.path.exists(summary_path):
        return None
    try:
        with open(summary_path) as f:
            summary = json.load(f)
    except (OSError, ValueError) as e:
        sys.exit(f"{summary_path}: not a readable JSON summary ({e})")
    if summary.get("settled_at_rest") is not False:
        return None
    ratio = summary.get("settle_unbalanced_force_ratio")
    after = summary.get("settle_s")
    details = ", ".join(d for d in (f"after {after:.1f} s of settling" if isinstance(after, (int, float)) else "",
                                    f"unbalanced-force ratio {ratio:.2g}" if isinstance(ratio, (int, float)) else "") if d)
    return "the net was not at rest when the platter started" + (f" ({details})" if details else "")


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
    left_out = []
    for path in files:
        metadata, rows = read_curve(path)
        x = [r["tool_displacement_mm"] / 1000.0 for r in rows]
        f = [r["tool_force_N"] / 1000.0 for r in rows]
        peak = max(range(len(f)), key=f.__getitem__)
        label = metadata.get("label") or path.rsplit("/", 1)[-1]
        why = not_applicable(x, f) or not_at_rest(path)
        if why:
            left_out.append(f"{label}: {why}")
            print(f"plot_punch: not drawn, not applicable in this set-up: {label}: {why}")
            continue
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
    if left_out:
        axes.text(0.01, 0.99, "not applicable in this set-up, not drawn:\n" + "\n".join(left_out),
                  transform=axes.transAxes, fontsize=7, va="top", ha="left", color="0.35")
    figure.tight_layout()
    figure.savefig(out, dpi=120, bbox_inches="tight")


if __name__ == "__main__":
    main()
