#!/usr/bin/env python3
"""`dtwire dem propagate` end to end on a small strip (experiments/dem/gap_selfcheck_strip.toml,
0.48 m wide, the pull cut to 60 mm: a few CPU seconds per run).

1. A fit whose only fitted parameter has zero variance: every drawn set is the fitted set, so the
   band is known exactly (both ends at the fitted set's figure, sd 0) and one DEM run serves all
   (the cache); that run's figures equal a plain `dem run --set-params` of the same file.
2. The same with --emulator and --samples auto: the emulator of a constant figure is that
   constant, so the emulated band is exactly the fitted set's figure and converges after three
   batches (its ends do not move); the files carry its columns.
3. Bad input exits 2 naming the file and field, or the option, before any run.

usage: dem_propagate_test.py DTWIRE SOURCE_DIR WORK_DIR
"""
import json
import os
import shutil
import subprocess
import sys


def main():
    dtwire, source, work = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    strip = os.path.join(source, "experiments/dem/gap_selfcheck_strip.toml")
    thesis = json.load(open(os.path.join(source, "experiments/data/macroelement_thesis_params.json")))
    parameters = [{"name": n, "value": v, "unit": "1", "sigma": None, "fitted": False}
                  for n, v in thesis["single_wire"].items()]
    for p in parameters:
        if p["name"] == "EA_N":
            p.update({"unit": "N", "sigma": 0.0, "lower": 1e6, "upper": 4e7, "fitted": True,
                      "identified": True, "coordinate": "log"})
    parameters.sort(key=lambda p: not p["fitted"])
    fit = {"law": "thesis", "wire_type": "single_wire", "parameters": parameters,
           "covariance_parameters": ["EA_N"], "covariance": [[0.0]]}
    fit_file = os.path.join(work, "parameters.json")
    json.dump(fit, open(fit_file, "w"))
    short = ["--set", "tool.travel_m=0.06"]

    out = os.path.join(work, "band")
    run = subprocess.run([dtwire, "dem", "propagate", strip, *short, "--params-fit", f"sw={fit_file}",
                          "--samples", "3", "--jobs", "2", "--no-plot", "-o", out],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stdout + run.stderr
    summary = json.load(open(os.path.join(out, "summary.json")))
    strength = summary["figures"][0]
    assert strength["key"] == "strength_per_width_kN_per_m", strength
    s = strength["sampled"]
    assert s["count"] == 3 and s["sd"] == 0.0, s
    assert s["q05"] == s["q95"] == strength["fitted_set"], strength
    assert summary["runs"]["dem_runs"] == 1 and summary["runs"]["cache_hits"] == 3, summary["runs"]
    assert summary["parameters"][0]["name"] == "sw.EA_N" and summary["parameters"][0]["sampled_as"] == "normal"
    for name in ("samples.csv", "convergence.csv", "sensitivity.csv", "band_curve.csv", "report.md"):
        assert os.path.getsize(os.path.join(out, name)) > 0, name
    header = open(os.path.join(out, "sensitivity.csv")).readline().strip().split(",")
    assert "derivative_figure_unit_per_parameter_unit" in header and "first_order_index_1" in header, header

    direct = os.path.join(work, "direct")
    plain = subprocess.run([dtwire, "dem", "run", strip, *short, "--set-params", f"sw={fit_file}", "--threads", "1",
                            "--no-frames", "-q", "-o", direct], capture_output=True, text=True)
    assert plain.returncode == 0, plain.stderr
    direct_summary = json.load(open(os.path.join(direct, "summary.json")))
    assert direct_summary["strength_per_width_kN_per_m"] == strength["fitted_set"], (direct_summary, strength)

    emulated = os.path.join(work, "emulated")
    run = subprocess.run([dtwire, "dem", "propagate", strip, *short, "--params-fit", f"sw={fit_file}",
                          "--samples", "auto", "--batch", "2", "--emulator", "--emulated-sets", "500", "--jobs", "2",
                          "--no-plot", "-o", emulated], capture_output=True, text=True)
    assert run.returncode == 0, run.stdout + run.stderr
    summary = json.load(open(os.path.join(emulated, "summary.json")))
    for figure in summary["figures"]:
        e = figure["emulated"]
        assert e["band"]["q05"] == e["band"]["q95"] == figure["fitted_set"], figure
        assert figure["emulator_converged"], figure
    assert summary["samples"]["drawn"] == 8, summary["samples"]  # emulated from 4 runs on (at least 3): rows 4, 6, 8
    assert summary["emulator"]["emulated_sets"] == 500, summary["emulator"]
    header = open(os.path.join(emulated, "convergence.csv")).readline()
    assert "strength_per_width_kN_per_m__emulated_q05" in header, header
    assert "## Emulated band" in open(os.path.join(emulated, "report.md")).read()

    # Bad input: exit 2, the file and field (or the option) named, nothing run.
    bad = dict(fit)
    bad["parameters"] = [dict(p) for p in parameters]
    bad["parameters"][0]["coordinate"] = "ln"
    bad_file = os.path.join(work, "bad.json")
    json.dump(bad, open(bad_file, "w"))
    cases = [
        (["--params-fit", f"sw={bad_file}"], [bad_file, "parameters[0].coordinate"]),
        (["--params-fit", f"sw={os.path.join(work, 'missing.json')}"], ["missing.json"]),
        (["--params-fit", f"wall={fit_file}"], ["--params-fit", "sw, dt or selvedge"]),
        (["--params-fit", f"sw={fit_file}", "--samples", "many"], ["--samples"]),
        (["--params-fit", f"sw={fit_file}", "--samples", "0"], ["--samples", "--linearised"]),
        (["--params-fit", f"sw={fit_file}", "--samples", "0", "--linearised", "--emulator"], ["--emulator", "sampled runs"]),
        (["--params-fit", f"sw={fit_file}", "--samples", "1", "--emulator"], ["--samples", "twice the parameter count"]),
    ]
    for extra, words in cases:
        r = subprocess.run([dtwire, "dem", "propagate", strip, *extra, "-o", os.path.join(work, "refused")],
                           capture_output=True, text=True)
        assert r.returncode == 2, (extra, r.returncode, r.stderr)
        for w in words:
            assert w in r.stderr, (extra, w, r.stderr)
    print("dem propagate: exact band of a zero-variance fit, one run for four sets, its emulated band, 7 refusals: ok")


if __name__ == "__main__":
    main()
