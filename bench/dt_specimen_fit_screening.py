#!/usr/bin/env python3
"""Timed run (not a test): the campaign step dt_specimen_fit with and without the multi-start's
screening stages (experiments/dt_fe_fit/dt_specimen_fit.toml, [fit] screening_*; docs/calibrate.md,
"Screening"), on the same FE curves, one after the other: CPU seconds (user + sys of the fit
process), wall seconds, simulator runs, best start and cost, and the ratios. The unscreened run
uses a copy of the file without the two screening lines. A start that passes the stages ends where
it ends unscreened, so when the best start passes, the two answers (parameters.json) are the same.
usage: bench/dt_specimen_fit_screening.py DTWIRE TARGETS OUT [--jobs N] [--only screened|unscreened]
TARGETS: a campaign's fem/dt_fe_fit folder (tension/curve.csv, pull_angle_47deg/curve.csv)."""
import json, os, re, resource, subprocess, sys, time

args = sys.argv[1:]
jobs = args[args.index("--jobs") + 1] if "--jobs" in args else "2"
only = args[args.index("--only") + 1] if "--only" in args else None
dtwire, targets, out = args[0], args[1], args[2]
here = os.path.dirname(os.path.abspath(__file__))
fit_file = os.path.join(here, "..", "experiments", "dt_fe_fit", "dt_specimen_fit.toml")
os.makedirs(out, exist_ok=True)
unscreened_file = os.path.join(os.path.dirname(fit_file), ".bench_unscreened_dt_specimen_fit.toml")
text = open(fit_file).read()
stripped = re.sub(r"(?m)^screening_(iterations|cost_ratio) = .*\n", "", text)
if stripped == text:
    sys.exit("bench: the fit file has no screening lines to remove")
with open(unscreened_file, "w") as f:  # beside the original: its relative paths stay valid
    f.write(stripped)

def run(name, file):
    folder = os.path.join(out, name)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.time()
    with open(os.path.join(out, name + ".log"), "w") as log:
        subprocess.run([dtwire, "fit", file, "--targets", targets, "--out", folder, "--jobs", jobs],
                       stdout=log, stderr=subprocess.STDOUT, check=True)
    wall = time.time() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    p = json.load(open(os.path.join(folder, "parameters.json")))
    log_text = open(os.path.join(out, name + ".log")).read()
    runs = re.findall(r"after (\d+) simulation runs", log_text)
    result = {"cpu_s": cpu, "wall_s": wall, "runs": int(runs[-1]) if runs else None, "file": p}
    print(f"{name}: {cpu:.1f} CPU s, {wall:.1f} s wall, {result['runs']} runs, load {os.getloadavg()[0]:.1f}", flush=True)
    return result

results = {}
try:
    if only in (None, "unscreened"):
        results["unscreened"] = run("unscreened", unscreened_file)
    if only in (None, "screened"):
        results["screened"] = run("screened", fit_file)
finally:
    os.remove(unscreened_file)
if len(results) == 2:
    u, s = results["unscreened"], results["screened"]
    print(f"ratio unscreened / screened: CPU {u['cpu_s'] / s['cpu_s']:.2f}, wall {u['wall_s'] / s['wall_s']:.2f}, "
          f"runs {u['runs'] / s['runs']:.2f}")
    same = json.dumps(u["file"].get("parameters"), sort_keys=True) == json.dumps(s["file"].get("parameters"), sort_keys=True)
    print("parameters.json parameters: " + ("the same" if same else "DIFFERENT (compare the two folders)"))
