#!/usr/bin/python3
"""Figure of the double-twist experiments (docs/fem_dt.md) from their `dtwire run` folders.

Usage: plot_dt_experiments.py RUNS_DIR OUT.png
RUNS_DIR holds one folder per experiment as `dtwire run experiments/dt/dt_<name>.prm --out
RUNS_DIR/<name>` writes them: tension, pull_angle, bending, compression, cyclic (a missing one
leaves its panel empty). Panels: (a) and (b) force against grip displacement and against the
twist's extensometer elongation, with the wire-wire contact normal force; (c) roller force
against its deflection; (d) compression; (f) cyclic tension under force control.
"""
import csv
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(folder):
    """Columns of curve.csv (or curve.partial.csv) by name, and the metadata."""
    for name in ("curve.csv", "curve.partial.csv"):
        path = folder / name
        if path.exists():
            break
    else:
        return None, {}
    metadata, body = {}, []
    for line in path.read_text().splitlines():
        if line.startswith("#"):
            key, _, value = line[1:].partition(":")
            metadata[key.strip()] = value.strip()
        elif line.strip():
            body.append(line)
    rows = list(csv.DictReader(body))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}, metadata


def failure_point(curve, metadata, x_column):
    if "failure" not in metadata:
        return None
    damage = curve.get("damage_1")
    index = next((i for i, d in enumerate(damage) if d >= 1.0), len(damage) - 1)
    return curve[x_column][index], curve["force_N"][index] / 1e3


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    runs, out = pathlib.Path(sys.argv[1]), sys.argv[2]
    fig, axes = plt.subplots(2, 2, figsize=(12, 8.5))
    ax = axes[0][0]
    tension, meta = read(runs / "tension")
    if tension:
        ax.plot(tension["displacement_mm"], [f / 1e3 for f in tension["force_N"]], "k-", label="(a) tension: grip displacement")
        if "extensometer_elongation_mm" in tension:
            ax.plot(tension["extensometer_elongation_mm"], [f / 1e3 for f in tension["force_N"]], "k:",
                    label="(a) tension: twist elongation (extensometer)")
        ax.plot(tension["displacement_mm"], [f / 1e3 for f in tension["wire_contact_normal_force_N"]], "b--",
                lw=1, label="(a) wire-wire contact normal force")
        point = failure_point(tension, meta, "displacement_mm")
        if point:
            ax.plot(*point, "rx", ms=10, label="failure indicator 1")
    pull, meta = read(runs / "pull_angle")
    if pull:
        ax.plot(pull["displacement_mm"], [f / 1e3 for f in pull["axial_force_N"]], "g-", lw=1,
                label="(b) pull at 47 deg: force along the pull")
        point = failure_point(pull, meta, "displacement_mm")
        if point:
            ax.plot(point[0], pull["axial_force_N"][pull["displacement_mm"].index(point[0])] / 1e3, "rx", ms=10)
    ax.set(xlabel="displacement (mm)", ylabel="force (kN)", title="DT tension (a), pull at 47 deg (b)")
    ax.legend(fontsize=8)
    ax = axes[0][1]
    bending, _ = read(runs / "bending")
    if bending:
        ax.plot([-u for u in bending["tool3_displacement_y_mm"]], bending["tool3_force_y_N"], "k-", label="loading roller")
        ax.plot([-u for u in bending["tool3_displacement_y_mm"]], [-f for f in bending["tool1_force_y_N"]], "c--", lw=1,
                label="support at z = -10 mm")
        ax.plot([-u for u in bending["tool3_displacement_y_mm"]], bending["wire_contact_normal_force_N"], "b:", lw=1,
                label="wire-wire contact normal force")
    ax.set(xlabel="loading roller deflection (mm)", ylabel="force (N)", title="(c) three-point bending, 20 mm rollers, span 60 mm")
    ax.legend(fontsize=8)
    ax = axes[1][0]
    compression, _ = read(runs / "compression")
    if compression:
        ax.plot([-u for u in compression["displacement_mm"]], [-f for f in compression["force_N"]], "k-", label="grips")
        ax.plot([-u for u in compression["displacement_mm"]], compression["wire_contact_normal_force_N"], "b:", lw=1,
                label="wire-wire contact normal force")
    ax.set(xlabel="shortening (mm)", ylabel="compressive force (N)", title="(d) compression, fixed ends")
    ax.legend(fontsize=8)
    ax = axes[1][1]
    cyclic, _ = read(runs / "cyclic")
    if cyclic:
        ax.plot(cyclic["displacement_mm"], [f / 1e3 for f in cyclic["force_N"]], "k-")
    ax.set(xlabel="grip displacement (mm)", ylabel="axial force (kN)", title="(f) cyclic tension, force control: 12 / 60 / 80 % of peak")
    for row in axes:
        for a in row:
            a.grid(alpha=0.3)
    fig.suptitle("Double twist, 2.7 mm wire, level-0 mesh (6426 DoFs)")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main()
