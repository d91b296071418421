#!/usr/bin/env python3
"""Which links carry a punch at its peak, per link type, for two parameter sets (issue 36).

usage: plot_link_loads.py OUT.png DTWIRE NAME=RUN_DIR:PARAMS.json NAME=RUN_DIR:PARAMS.json

RUN_DIR is a `dtwire dem run` punch folder (link_paths.csv, link_type_histograms.csv,
link_types_at_peak.csv, summary.json); PARAMS.json the thesis-format set file its SW and DT
links used. Per link type (columns SW, DT) the figure shows: the set's law replayed on an axial
pull (`DTWIRE dem driver --path axial_pull`) with the force-elongation paths of the run's most
loaded links (dots: at the punch's peak; the paths go on after it); the histograms of axial force and of total and plastic strain at the peak.
A markdown table of the per-type figures and of the parameters (second set / first set) goes
to stdout.
"""
import csv
import json
import os
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

TYPES = [("sw", "single_wire", "SW links (single wire)"), ("dt", "double_twist", "DT links (double twist)")]
PARAMETERS = ["EA_N", "N0_N", "Nult_N", "Nc_N", "k_F", "m_f", "EI_Nm2_per_deg_convention", "k_M", "W1_J", "W2_J"]
COLOURS = ["tab:blue", "tab:orange"]


def read_rows(path):
    with open(path, newline="") as handle:
        return list(csv.DictReader(line for line in handle if not line.startswith("#")))


def number(text):
    return float(text) if text not in ("", None) else None


def replay_axial_pull(dtwire, params, wire_type, folder):
    """Force against elongation of the set's law on a monotonic pull to 100 % of its reference length."""
    out = os.path.join(folder, wire_type)
    subprocess.run([dtwire, "dem", "driver", "--law", "thesis", "--params", params, "--wire-type", wire_type,
                    "--path", "axial_pull", "--max-strain", "1.0", "--steps", "4000", "--out", out],
                   check=True, stdout=subprocess.DEVNULL)
    rows = read_rows(os.path.join(out, "axial_pull.csv"))
    intact = [r for r in rows if float(r["broken_1"]) < 0.5]
    return [float(r["axial_displacement_mm"]) for r in intact], [float(r["axial_force_N"]) / 1000.0 for r in intact]


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    out, dtwire, specs = sys.argv[1], sys.argv[2], sys.argv[3:]
    sets = []
    for spec in specs:
        name, _, rest = spec.partition("=")
        run, _, params = rest.partition(":")
        sets.append({"name": name, "run": run, "params": params,
                     "paths": read_rows(os.path.join(run, "link_paths.csv")),
                     "histograms": read_rows(os.path.join(run, "link_type_histograms.csv")),
                     "at_peak": {r["link_type"]: r for r in read_rows(os.path.join(run, "link_types_at_peak.csv"))},
                     "summary": json.load(open(os.path.join(run, "summary.json"))),
                     "values": json.load(open(params))})

    figure, axes = plt.subplots(3, 2, figsize=(11, 11))
    with tempfile.TemporaryDirectory() as folder:
        for column, (tag, wire_type, title) in enumerate(TYPES):
            law_axes, force_axes, strain_axes = axes[0][column], axes[1][column], axes[2][column]
            for k, s in enumerate(sets):
                colour = COLOURS[k]
                x, f = replay_axial_pull(dtwire, s["params"], wire_type, os.path.join(folder, s["name"]))
                law_axes.plot(x, f, color=colour, linewidth=2.2, label=f"{s['name']}: law, axial pull")
                links = {}
                for r in s["paths"]:
                    if r["link_type"] == tag:
                        links.setdefault(r["link_id"], []).append((float(r["elongation_mm"]), float(r["force_N"]) / 1000.0))
                peak_mm = s["summary"]["displacement_at_peak_mm"]
                for i, path in enumerate(links.values()):
                    law_axes.plot([p[0] for p in path], [p[1] for p in path], color=colour, linewidth=0.6, alpha=0.6,
                                  linestyle="--", label=f"{s['name']}: {len(links)} most loaded links" if i == 0 else None)
                at_peak = [(float(r["elongation_mm"]), float(r["force_N"]) / 1000.0) for r in s["paths"]
                           if r["link_type"] == tag and abs(float(r["tool_displacement_mm"]) - peak_mm) < 1e-6]
                law_axes.plot([p[0] for p in at_peak], [p[1] for p in at_peak], "o", color=colour, markersize=4,
                              label=f"{s['name']}: those links at the punch's peak")
                rows = [r for r in s["histograms"] if r["link_type"] == tag]
                force = [(number(r["link_force_low_N"]) / 1000.0, number(r["link_force_high_N"]) / 1000.0,
                          number(r["force_count_at_peak_1"])) for r in rows if r["link_force_low_N"]]
                force_axes.stairs([c for _, _, c in force], [lo for lo, _, _ in force] + [force[-1][1]], color=colour,
                                  linewidth=1.6, label=s["name"])
                strain = [(number(r["strain_low_1"]) * 100.0, number(r["strain_high_1"]) * 100.0,
                           number(r["strain_count_at_peak_1"]), number(r["plastic_strain_count_at_peak_1"]))
                          for r in rows if r["strain_low_1"]]
                edges = [lo for lo, _, _, _ in strain] + [strain[-1][1]]
                strain_axes.stairs([t for _, _, t, _ in strain], edges, color=colour, linewidth=1.6,
                                   label=f"{s['name']}: total strain")
                if all(p is not None for _, _, _, p in strain):
                    strain_axes.stairs([p for _, _, _, p in strain], edges, color=colour, linewidth=1.0, linestyle=":",
                                       label=f"{s['name']}: plastic strain")
            law_axes.set_title(title)
            law_axes.set_xlabel("link elongation (mm)")
            law_axes.set_ylabel("axial force (kN)")
            law_axes.set_xlim(-1.0, 45.0)
            law_axes.set_ylim(bottom=0.0)
            force_axes.set_xlabel("axial force at the punch's peak (kN)")
            force_axes.set_ylabel("links")
            force_axes.set_yscale("log")
            strain_axes.set_xlabel("strain at the punch's peak (%, elongation / link length)")
            strain_axes.set_ylabel("links")
            strain_axes.set_yscale("log")
            for a in (law_axes, force_axes, strain_axes):
                a.grid(True, alpha=0.3)
                a.legend(fontsize=7)
    peaks = ", ".join(f"{s['name']} {s['summary']['peak_force_N'] / 1000:.1f} kN at {s['summary']['displacement_at_peak_mm']:.0f} mm"
                      for s in sets)
    figure.suptitle(f"Links at the punch's peak, slack state ({peaks})")
    figure.tight_layout()
    figure.savefig(out, dpi=110)

    # The table for docs/dem_engine.md.
    print("| set | link type | links (broken) | share of the tension at the peak | force p50 / p90 / max (kN) | "
          "strain p50 / p90 / max (%) | plastic strain p50 / p90 / max (%) | yielded |")
    print("|---|---|---|---|---|---|---|---|")
    for s in sets:
        total = sum(float(r["tension_sum_N"]) for r in s["at_peak"].values())
        for tag, _, _ in TYPES:
            r = s["at_peak"][tag]
            print(f"| {s['name']} | {tag} | {r['links_1']} ({r['broken_1']}) | {100 * float(r['tension_sum_N']) / total:.0f} % | "
                  f"{' / '.join(f'{float(r[k]) / 1000:.2f}' for k in ('force_p50_N', 'force_p90_N', 'force_max_N'))} | "
                  f"{' / '.join(f'{100 * float(r[k]):.2f}' for k in ('strain_p50_1', 'strain_p90_1', 'strain_max_1'))} | "
                  f"{' / '.join(f'{100 * float(r[k]):.2f}' for k in ('plastic_strain_p50_1', 'plastic_strain_p90_1', 'plastic_strain_max_1'))} | "
                  f"{r['yielded_1']} |")
    print()
    print(f"| parameter | set | {sets[0]['name']} | {sets[1]['name']} | ratio |")
    print("|---|---|---|---|---|")
    for _, wire_type, _ in TYPES:
        for p in PARAMETERS:
            a, b = sets[0]["values"][wire_type][p], sets[1]["values"][wire_type][p]
            print(f"| {p} | {wire_type} | {a:g} | {b:g} | {b / a:.3g} |")


if __name__ == "__main__":
    main()
