#!/usr/bin/python3
"""The double twist as made (issue 19): residual von Mises stress and equivalent plastic strain
along each wire after the springback (`as_made.csv` of `dtwire run` with As made/Forming
history = true), and the as-made against the tight tension curve.

Usage: plot_dt_as_made.py AS_MADE_RUN TIGHT_RUN OUT.png
Each RUN is a `dtwire run experiments/dt/dt_tension.prm --out RUN` folder (the as-made one with
--set "As made/Forming history=true"). The twist runs from z = 0 to 40 mm; the wires leave it
through 5.4 mm bends into the arms (the SW/DT junctions).
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt


def read(path):
    rows = [line for line in open(path) if not line.startswith("#")]
    return list(csv.DictReader(rows))


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    as_made, tight, out = sys.argv[1:]
    profile = read(f"{as_made}/as_made.csv")
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.2))
    for wire, colour in ((0, "tab:blue"), (1, "tab:orange")):
        rows = [r for r in profile if int(float(r["wire_1"])) == wire]
        z = [float(r["z_mm"]) for r in rows]
        label = "wire A" if wire == 0 else "wire B"
        axes[0].plot(z, [float(r["von_mises_max_MPa"]) for r in rows], color=colour, label=f"{label}, largest")
        axes[0].plot(z, [float(r["von_mises_mean_MPa"]) for r in rows], color=colour, ls="--", label=f"{label}, section mean")
        axes[1].plot(z, [float(r["plastic_strain_max_1"]) for r in rows], color=colour, label=f"{label}, largest")
        axes[1].plot(z, [float(r["plastic_strain_mean_1"]) for r in rows], color=colour, ls="--", label=f"{label}, section mean")
    for ax, title in ((axes[0], "residual von Mises stress (MPa)"), (axes[1], "equivalent plastic strain")):
        ax.axvspan(0, 40, color="0.92", zorder=0)
        ax.set_xlabel("height z along the twist axis (mm); twist 0-40 mm shaded")
        ax.set_title(title)
        ax.legend(fontsize=7)
    for run, label in ((tight, "tight, stress-free"), (as_made, "as made (formed, sprung back)")):
        rows = read(f"{run}/curve.csv")
        axes[2].plot([float(r["displacement_mm"]) for r in rows], [1e-3 * float(r["force_N"]) for r in rows], label=label)
    axes[2].set_xlabel("grip displacement (mm)")
    axes[2].set_ylabel("force (kN)")
    axes[2].set_title("DT tension, level-0 mesh")
    axes[2].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main()
