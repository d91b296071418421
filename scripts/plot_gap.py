#!/usr/bin/env python3
"""Plot of a gap diagnosis: laboratory curves, the simulation, the best augmented model and the
gap regions shaded. Called by `dtwire gap --plot OUT.png` with the data file it writes.

Usage: plot_gap.py DATA.plot.json OUT.png
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

REGION_COLOURS = {
    "toe": "#8dd3c7", "elastic": "#ffffb3", "yield": "#bebada", "hardening": "#fb8072",
    "peak": "#80b1d3", "post_peak": "#fdb462", "unloading": "#b3de69", "reloading": "#fccde5",
}


def main(data_path, png_path):
    with open(data_path, encoding="utf-8") as f:
        data = json.load(f)
    fig, ax = plt.subplots(figsize=(9, 5.5))
    shaded = set()
    for region in data["regions"]:
        name = region["region"]
        label = name if name not in shaded else None
        shaded.add(name)
        lo, hi = sorted((region["from_mm"], region["to_mm"]))
        ax.axvspan(lo, hi, color=REGION_COLOURS.get(name, "#d9d9d9"),
                   alpha=0.15 + 0.45 * region["share"], lw=0, label=label)
        if region["share"] >= 0.03:  # small shares would only overprint their neighbours
            ax.text(0.5 * (lo + hi), 1.0, f"{region['share']:.0%}",
                    transform=ax.get_xaxis_transform(), ha="center", va="bottom", fontsize=7)
    for i, lab in enumerate(data["labs"]):
        ax.plot(lab["displacement_mm"], lab["force_N"], ".", ms=2, color="0.35",
                label="laboratory" if i == 0 else None)
    sim = data["sim"]
    ax.plot(sim["displacement_mm"], sim["force_N"], "-", color="tab:blue", lw=1.6, label="simulation")
    best = data["best"]
    ax.plot(best["displacement_mm"], best["force_N"], "--", color="tab:red", lw=1.6,
            label=data["best_label"])
    ax.set_xlabel("displacement [mm]")
    ax.set_ylabel("force [N]")
    ax.set_title(f"gap {data['gap_before']:.4f} (noise floor {data['noise_floor']:.4f}), "
                 f"cause: {data['cause']}", fontsize=10, pad=14)
    ax.legend(fontsize=8, loc="lower right")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(png_path, dpi=120)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
