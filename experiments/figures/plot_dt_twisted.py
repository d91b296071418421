#!/usr/bin/python3
"""The double twist from the machine's twisting (issue 19): residual von Mises stress and
equivalent plastic strain along wire A after the release of the twisted pair and after the DT's
own springback with that state carried into its twist, against the bending-only forming; and
DT tension from the three starts.

Usage: plot_dt_twisted.py PAIR_RUN TWISTED_RUN BENDING_RUN TIGHT_RUN OUT.png
PAIR_RUN: `dtwire run experiments/dt/dt_twisting.prm --out PAIR_RUN` (released, as_made.csv);
TWISTED_RUN: `dtwire run experiments/dt/dt_tension.prm --set "As made/Forming history=true"
  --set "As made/Twisted pair state=PAIR_RUN/twisted_pair_state.csv" --out TWISTED_RUN`;
BENDING_RUN: the same without the twisted pair state; TIGHT_RUN: plain dt_tension.prm.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt


def read(path):
    return list(csv.DictReader(line for line in open(path) if not line.startswith("#")))


def wire_a(run):
    rows = [r for r in read(f"{run}/as_made.csv") if int(float(r["wire_1"])) == 0]
    return [float(r["z_mm"]) for r in rows], rows


def main():
    if len(sys.argv) != 6:
        sys.exit(__doc__)
    pair, twisted, bending, tight, out = sys.argv[1:]
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.2))
    for run, label, style, colour in ((pair, "twisted pair, released", ":", "tab:grey"),
                                      (twisted, "DT from the twisted pair", "-", "tab:green"),
                                      (bending, "DT, bending forming", "--", "tab:orange")):
        z, rows = wire_a(run)
        for ax, column in ((axes[0], "von_mises_mean_MPa"), (axes[1], "plastic_strain_mean_1")):
            ax.plot(z, [float(r[column]) for r in rows], ls=style, color=colour, label=label)
    for ax, title in ((axes[0], "wire A: residual von Mises stress, section mean (MPa)"),
                      (axes[1], "wire A: equivalent plastic strain, section mean")):
        ax.axvspan(0, 40, color="0.92", zorder=0)
        ax.set_xlabel("height z (mm); twist 0-40 mm shaded")
        ax.set_title(title, fontsize=10)
        ax.legend(fontsize=7)
    for run, label, colour in ((tight, "tight, stress-free", "tab:blue"), (bending, "bending forming", "tab:orange"),
                               (twisted, "from the twisted pair", "tab:green")):
        rows = read(f"{run}/curve.csv")
        axes[2].plot([float(r["displacement_mm"]) for r in rows], [1e-3 * float(r["force_N"]) for r in rows],
                     color=colour, label=label)
    axes[2].set_xlabel("grip displacement (mm)")
    axes[2].set_ylabel("force (kN)")
    axes[2].set_title("DT tension, level-0 mesh", fontsize=10)
    axes[2].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main()
