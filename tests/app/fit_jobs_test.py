#!/usr/bin/env python3
"""Issue 38: `dtwire fit --jobs 2` gives the parameters of `--jobs 1`, bit for bit.

usage: fit_jobs_test.py DTWIRE WORKDIR

A fit with a command simulator (each evaluation a subprocess in its own folder, as FE in the
loop through `dtwire run` is): a Python script computes a Voce bar's force-displacement curve
and sleeps 0.1 s, standing in for an FE run. Three starts, four parameters: with --jobs 2 the
starts and the finite-difference columns run side by side. The fit's results (parameters,
every start's end, cost, covariance) must be equal as written; the wall times are printed.
"""
import json
import os
import shutil
import subprocess
import sys
import time

SIMULATOR = r'''
import math, sys, time
values = dict(line.split("=") for line in open(sys.argv[1]).read().split())
E, sy, su, rate = (float(values[k]) for k in ("E", "sy", "su", "rate"))
area, length = 5.7256, 60.0  # mm2, mm
time.sleep(0.1)  # stands in for an FE run
with open(sys.argv[2] + "/curve.csv", "w") as out:
    out.write("displacement_mm,force_N\n")
    for i in range(41):
        u = 0.6 * i / 40
        strain = u / length
        plastic = 0.0
        for _ in range(60):  # stress = E (strain - plastic) = Voce(plastic)
            voce = sy + (su - sy) * (1 - math.exp(-rate * plastic))
            trial = E * (strain - plastic)
            if trial <= voce:
                break
            slope = E + (su - sy) * rate * math.exp(-rate * plastic)
            plastic += (trial - voce) / slope
        out.write(f"{u!r},{E * (strain - plastic) * area!r}\n")
'''

FIT = '''title = "Voce bar through a command simulator (fit --jobs test)"
wire_type = "single_wire"

[simulator]
kind = "command"
program = "{python}"
arguments = ["{script}", "{{input}}", "{{output}}"]
work_directory = "runs"

[fit]
starts = 3
seed = 5
max_iterations = 6
relative_step = 1e-4

[[parameter]]
name = "E"
unit = "MPa"
initial = 150000
lower = 100000
upper = 250000
reference = 190000

[[parameter]]
name = "sy"
unit = "MPa"
initial = 900
lower = 500
upper = 1500
reference = 1100

[[parameter]]
name = "su"
unit = "MPa"
initial = 1600
lower = 1200
upper = 2500
reference = 1800

[[parameter]]
name = "rate"
unit = "1"
initial = 40
lower = 5
upper = 200
reference = 80

[[experiment]]
name = "tension"
target = "{{targets}}/tension.csv"
input_template = "bar.in"
abscissa = "displacement"
channels = ["force"]
'''


def run(command, cwd):
    started = time.monotonic()
    result = subprocess.run(command, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if result.returncode != 0:
        sys.exit(f"FAIL: {' '.join(command)} exited {result.returncode}:\n{result.stdout}")
    return time.monotonic() - started


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    dtwire, work = (os.path.abspath(p) for p in sys.argv[1:])
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    with open(os.path.join(work, "voce_bar.py"), "w") as f:
        f.write(SIMULATOR)
    with open(os.path.join(work, "bar.in"), "w") as f:
        f.write("E={E}\nsy={sy}\nsu={su}\nrate={rate}\n")
    with open(os.path.join(work, "fit.toml"), "w") as f:
        f.write(FIT.format(python=sys.executable, script=os.path.join(work, "voce_bar.py")))
    run([dtwire, "fit", "fit.toml", "--synthesize", "targets", "--noise", "0.005", "--seed", "2"], work)
    results = {}
    for jobs in (1, 2):
        seconds = run([dtwire, "fit", "fit.toml", "--targets", "targets", "--out", f"jobs{jobs}", "--jobs", str(jobs)],
                      work)
        with open(os.path.join(work, f"jobs{jobs}", "parameters.json")) as f:
            results[jobs] = json.load(f)
        runs = results[jobs]["statistics"]
        print(f"--jobs {jobs}: {seconds:.1f} s, statistics {runs}")
    compared = ("parameters", "starts", "best_start", "cost", "covariance", "correlation", "residual_variance")
    different = [key for key in compared if results[1].get(key) != results[2].get(key)]
    if different:
        for key in different:
            print(f"{key}:\n  --jobs 1: {results[1].get(key)}\n  --jobs 2: {results[2].get(key)}")
        sys.exit(f"FAIL: --jobs 1 and --jobs 2 differ in {', '.join(different)}")
    values = {p["name"]: p["value"] for p in results[1]["parameters"]}
    print(f"OK: identical parameters {values}, {len(results[1]['starts'])} starts")
    return 0


if __name__ == "__main__":
    sys.exit(main())
