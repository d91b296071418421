#!/usr/bin/python3
"""DT three-point bending on rollers: the FE roller force against dem_specimen curves.

Usage: plot_dt_bending_rollers.py FE_CURVE.csv OUT.png LABEL=DEM_CURVE.csv ...

FE_CURVE: `dtwire run experiments/dt/dt_bending.prm` (tool3_displacement_y_mm, tool3_force_y_N);
DEM curves: `dtwire fit <file with the bending experiment> --synthesize DIR` (the same columns,
written through the fit file's mapping). Prints NRMSE (RMSE / FE range) and R^2 of each DEM
curve at the FE points and draws force (log axis: the DEM forces reach tens of kN) against the
roller's displacement along -y.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def read(path):
    rows = list(csv.DictReader(line for line in open(path) if not line.startswith("#")))
    return (np.array([-float(r["tool3_displacement_y_mm"]) for r in rows]),
            np.array([float(r["tool3_force_y_N"]) for r in rows]))


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    fe_x, fe_f = read(sys.argv[1])
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    ax.semilogy(fe_x, np.maximum(fe_f, 1.0), "k-", lw=2, label="FE (level 0)")
    for arg in sys.argv[3:]:
        label, path = arg.split("=", 1)
        x, f = read(path)
        residuals = np.interp(fe_x, x, f) - fe_f
        nrmse = np.sqrt(np.mean(residuals ** 2)) / (fe_f.max() - fe_f.min())
        r2 = 1.0 - np.sum(residuals ** 2) / np.sum((fe_f - fe_f.mean()) ** 2)
        print("%s: NRMSE %.3g, R^2 %.4g" % (label, nrmse, r2))
        ax.semilogy(x, np.maximum(f, 1.0), lw=1.5, label="%s (NRMSE %.2g)" % (label, nrmse))
    ax.set_xlabel("loading roller displacement along -y (mm)")
    ax.set_ylabel("roller force (N)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=120)


if __name__ == "__main__":
    main()
