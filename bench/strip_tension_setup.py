#!/usr/bin/env python3
"""Timed run (not a test): the strip tension of experiments/dem/strip_tension_thesis.toml in its
own set-up ("after") and in the set-up it had before issue 52 ("before": 1 cm/s, spin inertia
x 1, a row every 0.1 s), one after the other on one thread, with the thesis's published sets and,
if given, the recommended sets of a campaign's export folder (the default campaign's dem_strip_nm
step). Reports per run the CPU seconds (user + sys of the dtwire process), wall seconds, steps and
the three headline figures (strength per metre, secant EA 10-50 %, displacement at peak), then the
CPU ratio before / after and the figures' relative change (docs/dem_engine.md, "Strip tension").
usage: bench/strip_tension_setup.py DTWIRE OUT [--export DIR] [--only before|after]
DIR: a campaign's export_nm folder (single_wire_parameters.json, double_twist_parameters.json)."""
import json, os, resource, subprocess, sys, time

args = sys.argv[1:]
if len(args) < 2:
    sys.exit(__doc__)
dtwire, out = args[0], args[1]
export = args[args.index("--export") + 1] if "--export" in args else None
only = args[args.index("--only") + 1] if "--only" in args else None
here = os.path.dirname(os.path.abspath(__file__))
strip = os.path.join(here, "..", "experiments", "dem", "strip_tension_thesis.toml")
os.makedirs(out, exist_ok=True)

# The set-up before issue 52 (docs/validation.md, "Issue 52"): only the dynamics and the rows.
BEFORE = ["--set", "tool.speed_m_per_s=0.01", "--set", "dynamics.rotational_inertia_scale=1.0",
          "--set", "output.interval_s=0.1"]
sets = {"thesis": []}
if export:
    sets["recommended"] = ["--set-params", "sw=" + os.path.join(export, "single_wire_parameters.json"),
                           "--set-params", "dt=" + os.path.join(export, "double_twist_parameters.json")]
FIGURES = ("strength_per_width_kN_per_m", "secant_EA_10_50_kN_per_m", "displacement_at_peak_mm")


def run(name, extra):
    folder = os.path.join(out, name)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.time()
    subprocess.run([dtwire, "dem", "run", strip, *extra, "--threads", "1", "--no-frames", "-q", "-o", folder],
                   stdout=subprocess.DEVNULL, check=True)
    wall = time.time() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    s = json.load(open(os.path.join(folder, "summary.json")))
    print(f"{name}: {cpu:.1f} CPU s, {wall:.1f} s wall, {s['steps']} steps, " +
          ", ".join(f"{k} {s[k]:.4g}" for k in FIGURES) + f"; load {os.getloadavg()[0]:.1f}", flush=True)
    return cpu, s


for set_name, params in sets.items():
    results = {}
    for setup in ("before", "after"):
        if only in (None, setup):
            results[setup] = run(f"{set_name}_{setup}", params + (BEFORE if setup == "before" else []))
    if len(results) == 2:
        (cb, sb), (ca, sa) = results["before"], results["after"]
        print(f"{set_name}: CPU ratio before / after {cb / ca:.2f}, steps {sb['steps'] / sa['steps']:.2f}; " +
              ", ".join(f"{k} {100 * (sa[k] / sb[k] - 1):+.2f} %" for k in FIGURES), flush=True)
