#!/usr/bin/env python3
"""The punch figure leaves out a run that does not apply to its set-up (issue 52): a curve that
still rises when the platter stops (the WirePM sets in the slack state), never carries 1 kN, or
whose run's summary.json says its net was not at rest when the platter started is named as not
applicable, not drawn as a result; a curve with a peak within its travel is drawn.

usage: plot_punch_test.py DTWIRE WORKDIR
"""
import json
import os
import shutil
import subprocess
import sys


def curve(path, label, rows):
    with open(path, "w") as f:
        f.write(f"# label: {label}\ntool_displacement_mm,tool_force_N\n")
        f.writelines(f"{x},{force}\n" for x, force in rows)


def main():
    dtwire, work = sys.argv[1:]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    peaked = os.path.join(work, "peaked.csv")
    rising = os.path.join(work, "rising.csv")
    weak = os.path.join(work, "weak.csv")
    curve(peaked, "thesis published", [(0, 0), (200, 1000), (548, 45000), (600, 20000), (750, 5000)])
    curve(rising, "WirePM published", [(0, 0), (250, 100), (510, 250), (750, 1770)])
    curve(weak, "weak set", [(0, 0), (250, 900), (510, 300), (750, 200)])
    moving_run = os.path.join(work, "moving")
    os.makedirs(moving_run)
    moving = os.path.join(moving_run, "curve.csv")
    curve(moving, "moving net", [(0, 0), (300, 1000), (760, 67000), (800, 20000), (1200, 5000)])
    with open(os.path.join(moving_run, "summary.json"), "w") as f:
        json.dump({"settled_at_rest": False, "settle_s": 120.0, "settle_unbalanced_force_ratio": 0.0046}, f)
    figure = os.path.join(work, "punch.png")
    run = subprocess.run([dtwire, "dem", "plot-punch", figure, peaked, rising, weak, moving], capture_output=True, text=True)
    print(run.stdout + run.stderr)
    failures = []
    if run.returncode != 0 or not os.path.exists(figure):
        failures.append(f"plot-punch failed (exit {run.returncode})")
    lines = run.stdout.splitlines()
    left_out = [line for line in lines if line.startswith("plot_punch: not drawn")]
    if not any("WirePM published" in line and "no peak within the travel" in line for line in left_out):
        failures.append("the WirePM run that still rises at the end of its travel is not named as not applicable")
    if not any("weak set" in line and "onset force" in line for line in left_out):
        failures.append("the run that never carries 1 kN is not named as not applicable")
    if not any("moving net" in line and "not at rest" in line and "0.0046" in line for line in left_out):
        failures.append("the run whose net was still moving when the platter started is not named as not applicable")
    if any("thesis published" in line for line in left_out):
        failures.append("the run with a peak within its travel was left out")
    for failure in failures:
        print("FAIL: " + failure)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
