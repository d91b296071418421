#!/usr/bin/env python3
"""Timed run (not a test): the slack-state macro-element punch of the stop's comparison (issue 52:
experiments/dem/punch_macro.toml, no pre-tension, wall 0.1 m below, 40 s of settling as the
campaign had it before it settled to rest, platter kn 1e8, ks 1e7) by two builds, one after the other on one
thread: "before" (e.g. main's dtwire, the whole 0.75 m of travel) and "after" (this branch's, with
the campaign's tool.stop_below_peak_fraction), with the thesis's published sets and, if given,
the recommended sets of a campaign's export folder. Reports per run the CPU seconds (user + sys
of the dtwire process), wall seconds, steps, the sag after settling and the three headline
figures (peak force, displacement at peak, onset), then the CPU ratio before / after, the
figures' changes and the largest force difference up to the peak row by row, in % of the peak
(docs/dem_engine.md, "Speed of the 3 x 3 m macro-element punch").
usage: bench/punch_setup.py BEFORE_DTWIRE AFTER_DTWIRE OUT [--export DIR] [--only before|after]
DIR: a campaign's export_nm folder (single_wire_parameters.json, double_twist_parameters.json)."""
import csv, json, os, resource, subprocess, sys, time

args = sys.argv[1:]
if len(args) < 3:
    sys.exit(__doc__)
dtwire = {"before": args[0], "after": args[1]}
out = args[2]
export = args[args.index("--export") + 1] if "--export" in args else None
only = args[args.index("--only") + 1] if "--only" in args else None
here = os.path.dirname(os.path.abspath(__file__))
punch = os.path.join(here, "..", "experiments", "dem", "punch_macro.toml")
os.makedirs(out, exist_ok=True)

# The campaign's set-up (experiments/default/campaign.toml, dem_punch_thesis); "after" adds the
# stop at the net's failure.
SETUP = ["--set", "boundary.pretension_strain=0.0", "--set", "boundary.wall_below_m=0.1", "--set",
         "dynamics.settle_s=40.0", "--set", "tool.kn_N_per_m=1e8", "--set", "tool.ks_N_per_m=1e7"]
AFTER = ["--set", "tool.stop_below_peak_fraction=0.5"]
sets = {"thesis": []}
if export:
    sets["recommended"] = ["--set-params", "sw=" + os.path.join(export, "single_wire_parameters.json"),
                           "--set-params", "dt=" + os.path.join(export, "double_twist_parameters.json")]
FIGURES = ("peak_force_N", "displacement_at_peak_mm", "onset_displacement_mm")


def curve(folder):
    rows = [line for line in open(os.path.join(folder, "curve.csv")) if not line.startswith("#")]
    table = list(csv.DictReader(rows))
    return [float(r["tool_displacement_mm"]) for r in table], [float(r["tool_force_N"]) for r in table]


def run(name, setup, extra):
    folder = os.path.join(out, name)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.time()
    subprocess.run([dtwire[setup], "dem", "run", punch, *SETUP, *extra, "--threads", "1", "--no-frames", "-q",
                    "-o", folder], stdout=subprocess.DEVNULL, check=True)
    wall = time.time() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    s = json.load(open(os.path.join(folder, "summary.json")))
    print(f"{name}: {cpu:.1f} CPU s, {wall:.1f} s wall, {s['steps']} steps, sag {s['sag_after_settling_mm']:.2f} mm, "
          + ", ".join(f"{k} {s[k]:.5g}" for k in FIGURES) + f", end {curve(folder)[0][-1]:.0f} mm, "
          f"{s['broken_links']} broken; load {os.getloadavg()[0]:.1f}", flush=True)
    return cpu, s, folder


for set_name, params in sets.items():
    results = {}
    for setup in ("before", "after"):
        if only in (None, setup):
            results[setup] = run(f"{set_name}_{setup}", setup, params + (AFTER if setup == "after" else []))
    if len(results) == 2:
        (cb, sb, fb), (ca, sa, fa) = results["before"], results["after"]
        (ub, f_b), (ua, f_a) = curve(fb), curve(fa)
        peak_row = f_b.index(max(f_b))
        rows = min(peak_row + 1, len(f_a))
        worst = max(range(rows), key=lambda r: abs(f_a[r] - f_b[r]))
        print(f"{set_name}: CPU ratio before / after {cb / ca:.2f}, steps {sb['steps'] / sa['steps']:.2f}; "
              f"peak {100 * (sa['peak_force_N'] / sb['peak_force_N'] - 1):+.2f} %, at "
              f"{sa['displacement_at_peak_mm'] - sb['displacement_at_peak_mm']:+.1f} mm, onset "
              f"{100 * (sa['onset_displacement_mm'] / sb['onset_displacement_mm'] - 1):+.2f} %; largest force "
              f"difference up to the peak {100 * abs(f_a[worst] - f_b[worst]) / sb['peak_force_N']:.2f} % of the peak "
              f"at {ub[worst]:.1f} mm (displacements differ by up to "
              f"{max(abs(ua[r] - ub[r]) for r in range(rows)):.2g} mm)", flush=True)
