#!/usr/bin/env python3
"""Issue 38: a small campaign run one step at a time, side by side, and as a Snakemake workflow
writes the same files.

usage: campaign_parallel_test.py DTWIRE CAMPAIGN.toml WORKDIR (--jobs | --snakemake)

--jobs: `dtwire campaign --jobs 1` and `--jobs 2` into two folders; the file trees must match
(after normalisation, below), and the two fits (steps fit_a and fit_b, independent) must overlap
in time with --jobs 2 and not with --jobs 1 (from the start offsets and wall times the runner
saves in campaign_state.json; no timing margin is involved: side by side both start together).

--snakemake: `dtwire campaign --snakefile`, then `snakemake --cores 2`; the tree must match the
runner's. Exits 77 (ctest: skipped) when snakemake is not installed (scripts/setup installs it).

Normalisation: the output folder's own path becomes {out}; ISO times, wall times and the run's
durations are masked, and so is the critical path, which follows them (in report.md and in its
HTML form); report.html's embedded images are masked (the PNG files themselves are compared byte
for byte); files that only hold times (campaign.lock, Snakemake's benchmark.tsv) are compared by
presence, campaign_state.json by its steps and their status. HDF5 files are compared by their
h5dump text (hdf5-tools, which scripts/setup installs), normalised as the text files are and with
the SHA-256 of each input (an input such as a parameters.json names its run id) and the declared
sizes of strings masked too: their size alone depends on the lengths of the paths they record. Without h5dump, by size.
"""
import json
import os
import re
import shutil
import subprocess
import sys
import time

SKIP = 77
# Files that only record when and how long: compared by presence, or not at all.
TIMING_ONLY = {"campaign.lock"}
SNAKEMAKE_ONLY = re.compile(r"^steps/[^/]+/benchmark\.tsv$")
# The runner's fingerprint of a step's command and inputs (for resuming a fit): the command names
# the output folder, and Snakemake keeps its own.
RUNNER_ONLY = re.compile(r"^steps/[^/]+/fingerprint$")


def run(command, **kwargs):
    started = time.monotonic()
    result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, **kwargs)
    seconds = time.monotonic() - started
    if result.returncode != 0:
        sys.exit(f"FAIL: {' '.join(command)} exited {result.returncode}:\n{result.stdout}")
    return result.stdout, seconds


def tree(folder):
    files = {}
    for root, _, names in os.walk(folder):
        for name in names:
            path = os.path.join(root, name)
            files[os.path.relpath(path, folder)] = path
    return files


MASKS = [
    (re.compile(r"\d{8}T\d{6}Z-\d+-[0-9a-f]+"), "<run id>"),
    (re.compile(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d(\.\d+)?Z?"), "<time>"),
    # Wall times and durations: "12.3 s", "\"seconds\": 0.41", "\"wall_seconds\": 2.1", step table cells.
    (re.compile(r"\d+(\.\d+)?(e[+-]?\d+)? s\b"), "<t> s"),
    (re.compile(r"(\"[a-z_]*seconds\"\s*:\s*)[0-9.e+-]+"), r"\1<t>"),
    (re.compile(r"(\| (done|up to date) \| )[0-9.]+( \|)"), r"\1<t>\3"),
    (re.compile(r"(<td>(done|up to date)</td><td>)[0-9.]+(</td>)"), r"\1<t>\3"),
    # The critical path follows the step times (two steps of equal work may swap places).
    (re.compile(r"\*\*Critical path\*\*[^\n]*"), "<critical path>"),
    (re.compile(r'(?s)"critical_path": \{.*?\n  \}'), '"critical_path": <critical path>'),
    (re.compile(r"<strong>Critical path</strong>.*?</p>", re.S), "<critical path>"),
    # report.html embeds the figures, which are compared as files.
    (re.compile(r"data:image/[a-z+]+;base64,[A-Za-z0-9+/=]+"), "<image>"),
]


def normalised(path, out):
    with open(path, "rb") as f:
        data = f.read()
    try:
        text = data.decode()
    except UnicodeDecodeError:
        return data  # binary (HDF5, PNG): compared byte for byte
    text = text.replace(os.path.abspath(out), "{out}")
    for pattern, replacement in MASKS:
        text = pattern.sub(replacement, text)
    return text


SHA256 = re.compile(r'"[0-9a-f]{64}"')
# A fixed-length string's declared size follows the paths it holds; its text is compared.
STRSIZE = re.compile(r"STRSIZE \d+;")


def hdf5_text(path, out):
    """The file's h5dump text, normalised; the dump's first line names the file itself."""
    dump = subprocess.run(["h5dump", path], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True).stdout
    text = dump.split("\n", 1)[1].replace(os.path.abspath(out), "{out}")
    for pattern, replacement in MASKS + [(SHA256, '"<sha256>"'), (STRSIZE, "STRSIZE <n>;")]:
        text = pattern.sub(replacement, text)
    return text


def state_summary(path):
    with open(path) as f:
        state = json.load(f)
    # The fingerprints hash the commands, which name the output folder.
    return {step: entry["status"] for step, entry in state.items()}


def compare(a, b):
    files_a, files_b = tree(a), tree(b)
    names_a = {n for n in files_a if not SNAKEMAKE_ONLY.match(n) and not RUNNER_ONLY.match(n)}
    names_b = {n for n in files_b if not SNAKEMAKE_ONLY.match(n) and not RUNNER_ONLY.match(n)}
    problems = []
    for name in sorted(names_a ^ names_b):
        problems.append(f"only in {a if name in names_a else b}: {name}")
    for name in sorted(names_a & names_b):
        if name in TIMING_ONLY:
            continue
        if name == "campaign_state.json":
            sa, sb = state_summary(files_a[name]), state_summary(files_b[name])
            if sa != sb:
                problems.append(f"{name}: steps differ:\n  {sa}\n  {sb}")
            continue
        if name.endswith(".h5") and not shutil.which("h5dump"):
            if abs(os.path.getsize(files_a[name]) - os.path.getsize(files_b[name])) > 64:
                problems.append(f"{name}: sizes {os.path.getsize(files_a[name])} and {os.path.getsize(files_b[name])}")
            continue
        if name.endswith(".h5"):
            if hdf5_text(files_a[name], a) != hdf5_text(files_b[name], b):
                problems.append(f"{name}: contents differ (diff <(h5dump {files_a[name]}) <(h5dump {files_b[name]}))")
            continue
        if normalised(files_a[name], a) != normalised(files_b[name], b):
            problems.append(f"{name}: contents differ (diff {files_a[name]} {files_b[name]})")
    return len(names_a & names_b), problems


def main():
    if len(sys.argv) != 5 or sys.argv[4] not in ("--jobs", "--snakemake"):
        sys.exit(__doc__)
    dtwire, campaign, work, mode = sys.argv[1:]
    # Absolute, as the workflow names them (the report names the campaign file as given).
    dtwire, campaign, work = (os.path.abspath(p) for p in (dtwire, campaign, work))
    if mode == "--snakemake" and not shutil.which("snakemake"):
        print("SKIP: snakemake is not installed (scripts/setup installs Debian's snakemake)")
        return SKIP
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    serial = os.path.join(work, "jobs1")
    _, t1 = run([dtwire, "campaign", campaign, "-o", serial, "--jobs", "1"])
    print(f"--jobs 1: {t1:.1f} s")
    if mode == "--jobs":
        parallel = os.path.join(work, "jobs2")
        console, t2 = run([dtwire, "campaign", campaign, "-o", parallel, "--jobs", "2"])
        print(f"--jobs 2: {t2:.1f} s")
        print(console)
        for folder, side_by_side in ((serial, False), (parallel, True)):
            with open(os.path.join(folder, "campaign_state.json")) as f:
                state = json.load(f)
            a, b = state["fit_a"], state["fit_b"]
            overlap = a["started_s"] < b["started_s"] + b["seconds"] and b["started_s"] < a["started_s"] + a["seconds"]
            print(f"{folder}: fit_a {a['started_s']:.2f} + {a['seconds']:.2f} s, fit_b {b['started_s']:.2f} + "
                  f"{b['seconds']:.2f} s: {'overlap' if overlap else 'one after the other'}")
            if overlap != side_by_side:
                sys.exit(f"FAIL: fit_a and fit_b {'do not overlap' if side_by_side else 'overlap'} in {folder}")
        other = parallel
    else:
        other = os.path.join(work, "snakemake")
        snakefile = os.path.join(work, "Snakefile")
        run([dtwire, "campaign", campaign, "-o", other, "--snakefile", snakefile])
        if os.path.exists(other):
            sys.exit(f"FAIL: --snakefile wrote into {other}")
        _, ts = run(["snakemake", "-s", snakefile, "--cores", "2", "-d", os.path.join(work, "snakemake_work")])
        print(f"snakemake --cores 2: {ts:.1f} s")
    count, problems = compare(serial, other)
    if problems:
        sys.exit("FAIL:\n" + "\n".join(problems))
    print(f"OK: {count} files match between {serial} and {other}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
