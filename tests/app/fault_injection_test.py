#!/usr/bin/env python3
"""Issue 53: faults lose nothing. Kills and starves dtwire at random points and checks that the
outputs after a resume equal an uninterrupted run's, that no process outlives its campaign, that
no temporary file stays and that every result folder holds one run id.

usage: fault_injection_test.py DTWIRE SOURCE_DIR WORKDIR [SEED]

Cases (each prints one line; the kill times are drawn from SEED, default 53, and printed):
  campaign-kill   SIGKILL to the campaign runner's process group (a batch scheduler, a closed
                  terminal) at 3 random moments of a small campaign; no step may outlive it, the
                  same command resumes (an interrupted fit with --resume), the final folder equals
                  the uninterrupted run's
  campaign-int    SIGINT to the runner: exit 130, then a clean resume
  two-campaigns   a second campaign into the same folder is refused (exit 2) while the first runs,
                  and the first ends as an uninterrupted run
  dem-kill        SIGKILL to a `dem run` (a small strip) at 2 random moments, then the same command
  fit-kill        SIGKILL to a fit at 2 random moments, then `fit --resume`
  file-size       `dem run`, `fit` and the campaign under a file-size limit (ulimit -f, a full disk
                  for a writer): exit 1 naming the file and "File too large", no temporary and no
                  partial result left; rerun without the limit equals the reference
  full-disk       `fit` and `dem run` into a 1 MiB tmpfs (needs root; reported as skipped
                  otherwise): exit 1 with "No space left on device"
Comparison: the normalisation of campaign_parallel_test.py (run ids, ISO times, wall times
masked; HDF5 files by their h5dump text), besides which the steps' console logs and command.txt (a resumed
step's differ by design), steps/<step>/fingerprint (it hashes the command, which names the
output folder), the fit's simulation counters (a resumed fit runs fewer simulations; the
parameters, costs and curves are compared) and a step's "up to date" for "done" in the report
are left out.
"""
import os
import random
import re
import resource
import shutil
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import campaign_parallel_test as parallel  # noqa: E402  (its tree comparison and masks)

TEMPORARY = re.compile(r"\.tmp\.\d+\.\d+$")
RUN_ID = re.compile(rb"\d{8}T\d{6}Z-\d+-[0-9a-f]{8}")
CRASH_CODES = {134, 136, 137, 139, 153, -6, -8, -9, -11, -25}  # abort, FPE, kill, segfault, SIGXFSZ
# A resumed step's console log and command line differ by design; a resumed fit counts only its
# own simulations; a step finished before the interruption is "up to date" in the resumed
# campaign's report where the uninterrupted one says "done".
parallel.MASKS += [
    (re.compile(r"\d+ steps?, \d+ (done|up to date)(, \d+ (done|up to date))?"), "<steps>"),
    (re.compile(r"\bup to date\b"), "done"),
    (re.compile(r'("(simulations|cache_hits|failed_simulations)"\s*:\s*)\d+'), r"\1<n>"),
    (re.compile(r'("failure_kinds"\s*:\s*)\{[^}]*\}'), r"\1<kinds>"),
    (re.compile(r"\d+ simulation runs \(\d+ cache hits, \d+ failed\)"), "<runs>"),
]
LEFT_OUT = re.compile(r"^steps/[^/]+/(output\.log|command\.txt|fingerprint)$|(^|/)cache/|^campaign\.lock$")


def log(text):
    print(text, flush=True)


def processes_naming(fragment):
    """pids of the processes whose command line contains `fragment` (a folder path)."""
    found = []
    for pid in os.listdir("/proc"):
        if not pid.isdigit() or int(pid) == os.getpid():
            continue
        try:
            with open(f"/proc/{pid}/cmdline", "rb") as f:
                if fragment.encode() in f.read():
                    found.append(int(pid))
        except OSError:
            pass
    return found


def wait_none_naming(fragment, seconds):
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        if not processes_naming(fragment):
            return []
        time.sleep(0.1)
    return processes_naming(fragment)


def temporaries(folder):
    return [os.path.join(root, name) for root, dirs, files in os.walk(folder) for name in files + dirs
            if TEMPORARY.search(name)]


def run_ids_per_folder(folder):
    """{folder: run ids} for each result folder holding more than one (the campaign's own files and
    the steps' logs name several runs by design)."""
    mixed = {}
    for root, _, files in os.walk(folder):
        rel = os.path.relpath(root, folder)
        if rel == "." or rel.startswith("steps") or rel.endswith("cache") or "/cache/" in rel:
            continue
        ids = set()
        for name in files:
            with open(os.path.join(root, name), "rb") as f:
                ids |= set(RUN_ID.findall(f.read()))
        if len(ids) > 1:
            mixed[rel] = sorted(i.decode() for i in ids)
    return mixed


def compare(reference, other):
    """The problems between two result folders (parallel.compare without the left-out files)."""
    saved = parallel.tree

    def tree(folder):
        return {n: p for n, p in saved(folder).items() if not LEFT_OUT.search(n)}

    parallel.tree = tree
    try:
        count, problems = parallel.compare(reference, other)
    finally:
        parallel.tree = saved
    return count, problems


def check_folder(reference, folder, what):
    problems = [f"{what}: {p}" for p in compare(reference, folder)[1]]
    problems += [f"{what}: temporary left: {t}" for t in temporaries(folder)]
    problems += [f"{what}: {rel} holds run ids {ids}" for rel, ids in run_ids_per_folder(folder).items()]
    return problems


def run(command, limit_blocks=None, **kwargs):
    def limit():
        if limit_blocks is not None:
            resource.setrlimit(resource.RLIMIT_FSIZE, (limit_blocks * 1024, limit_blocks * 1024))
    started = time.monotonic()
    result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                            preexec_fn=limit, **kwargs)
    return result.returncode, result.stdout, time.monotonic() - started


def must_succeed(command):
    code, output, seconds = run(command)
    if code != 0:
        sys.exit(f"FAIL: {' '.join(command)} exited {code}:\n{output}")
    return seconds


def kill_after(command, delay, signal_number=signal.SIGKILL, group=True):
    """Starts `command` in its own session, sends the signal after `delay` s (to its process group
    or its pid), returns (exit code, console)."""
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                               start_new_session=True)
    try:
        process.wait(timeout=delay)
    except subprocess.TimeoutExpired:
        (os.killpg if group else os.kill)(process.pid, signal_number)
    console, _ = process.communicate(timeout=120)
    kill_after.last_pid = process.pid
    return process.returncode, console


def plant_temporaries(folder, names, pid):
    """What a writer killed inside a write leaves (a random kill rarely lands there): half a file
    under NAME.tmp.PID.N, PID the killed process's."""
    planted = []
    for name in names:
        path = os.path.join(folder, f"{name}.tmp.{pid}.99")
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w") as f:
            f.write("# run_id = 20260101T000000Z-1-0badc0de\nhalf a ro")
        planted.append(path)
    return planted


class Cases:
    def __init__(self, dtwire, source, work, seed):
        self.dtwire, self.source, self.work = dtwire, source, work
        self.random = random.Random(seed)
        self.problems = []
        self.campaign = os.path.join(source, "tests/app/data/fault_campaign/campaign.toml")
        self.fit_file = os.path.join(source, "tests/app/data/fault_campaign/fit.toml")
        self.strip = os.path.join(source, "experiments/dem/strip_tension_across.toml")
        # The campaign's strip step: 1 cm of travel at 5 cm/s, three frames, one thread.
        self.strip_settings = ["--set", "tool.travel_m=0.01", "--set", "tool.speed_m_per_s=0.05",
                               "--set", "output.frames=3", "--threads", "1", "-q"]

    def folder(self, name):
        """A fresh folder in the work folder."""
        path = os.path.join(self.work, name)
        shutil.rmtree(path, ignore_errors=True)
        return path

    def campaign_command(self, out):
        return [self.dtwire, "campaign", self.campaign, "-o", out]

    def fit_command(self, out, targets):
        return [self.dtwire, "fit", self.fit_file, "--targets", targets, "--out", out, "--jobs", "1"]

    def dem_command(self, out):
        return [self.dtwire, "dem", "run", self.strip, *self.strip_settings, "-o", out]

    def fail(self, case, text):
        self.problems.append(f"{case}: {text}")
        log(f"  FAIL {text}")

    # ---- references ------------------------------------------------------------------------
    def references(self):
        self.reference = self.folder("reference_campaign")
        self.campaign_seconds = must_succeed(self.campaign_command(self.reference))
        self.targets = os.path.join(self.reference, "targets")
        self.fit_reference = self.folder("reference_fit")
        self.fit_seconds = must_succeed(self.fit_command(self.fit_reference, self.targets))
        self.dem_reference = self.folder("reference_dem")
        self.dem_seconds = must_succeed(self.dem_command(self.dem_reference))
        log(f"references: campaign {self.campaign_seconds:.1f} s, fit {self.fit_seconds:.1f} s, "
            f"dem run {self.dem_seconds:.1f} s")

    # ---- cases -----------------------------------------------------------------------------
    def start_and_kill_when(self, command, trigger, delay, signal_number=signal.SIGKILL, group=True):
        """Starts `command` in its own session and, `delay` s after trigger() first holds, sends
        the signal to its process group (or pid). Returns (exit code, console)."""
        process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                                   start_new_session=True)
        while not trigger() and process.poll() is None:
            time.sleep(0.002)
        time.sleep(delay)
        if process.poll() is None:
            (os.killpg if group else os.kill)(process.pid, signal_number)
        console, _ = process.communicate(timeout=300)
        return process.returncode, console

    def campaign_kill(self):
        for round_number in range(3):
            out = self.folder(f"campaign_kill_{round_number}")
            command = self.campaign_command(out)
            delay = self.random.uniform(0.0, 0.3)
            if round_number == 0:  # inside the fit, after its first checkpoint
                checkpoint = os.path.join(out, "fit", "checkpoint.json")
                code, _ = self.start_and_kill_when(command, lambda: os.path.exists(checkpoint), delay)
                moment = f"{delay:.2f} s after the fit's first checkpoint"
            elif round_number == 1:  # while the strip runs
                strip = os.path.join(out, "strip")
                code, _ = self.start_and_kill_when(command, lambda: bool(processes_naming(strip)), delay + 1.0)
                moment = f"{delay + 1.0:.2f} s into the strip step"
            else:
                delay = self.random.uniform(0.1, 0.9) * self.campaign_seconds
                code, _ = kill_after(command, delay)
                moment = f"{delay:.2f} s"
            # A step dies with its runner: a fit ends its iteration and saves its checkpoint. An
            # orphan shows as a process naming the folder 5 s on, or as a step that finished
            # (wrote its last output) after its runner was killed.
            killed_at = time.time()
            orphans = wait_none_naming(out, 5)
            if orphans:
                self.fail("campaign-kill", f"steps outlive the killed runner by 5 s: {orphans}")
                for pid in orphans:
                    os.kill(pid, signal.SIGKILL)
            for last_output in ("fit/parameters.json", "strip/summary.json"):
                path = os.path.join(out, last_output)
                if os.path.exists(path) and os.path.getmtime(path) > killed_at:
                    orphans = orphans or [last_output]
                    self.fail("campaign-kill", f"{last_output} was written after the runner was killed (an orphan step)")
            if round_number == 1:
                planted = plant_temporaries(os.path.join(out, "strip"), ["curve.csv", "frames/net_2.vtu"], 999999999)
            interrupted_fit = os.path.exists(os.path.join(out, "fit", "checkpoint.json")) and not os.path.exists(
                os.path.join(out, "fit", "parameters.json"))
            code2, console, _ = run(command)
            if code2 != 0:
                self.fail("campaign-kill", f"resume exited {code2}:\n{console}")
            if round_number == 1 and any(os.path.exists(p) for p in planted):
                self.fail("campaign-kill", "the killed strip's temporaries outlive the resume")
            resumed = "--resume" in open(os.path.join(out, "steps", "fit", "command.txt")).read()
            if interrupted_fit and not resumed:
                self.fail("campaign-kill", "the interrupted fit started afresh, not from its checkpoint")
            for problem in check_folder(self.reference, out, f"kill at {moment}"):
                self.fail("campaign-kill", problem)
            log(f"campaign-kill at {moment}: exit {code}, "
                f"{'orphans ' + str(orphans) if orphans else 'no step outlived the runner'}, resume exit {code2}"
                f"{', the fit resumed from its checkpoint' if resumed else ''}")

    def campaign_interrupt(self):
        out = self.folder("campaign_int")
        delay = self.random.uniform(0.2, 0.8) * self.campaign_seconds
        code, console = kill_after(self.campaign_command(out), delay, signal.SIGINT, group=False)
        if code not in (0, 130):  # 0: the campaign had finished
            self.fail("campaign-int", f"exit {code}, expected 130:\n{console}")
        if code == 130 and "campaign interrupted" not in console:
            self.fail("campaign-int", "no 'campaign interrupted' message")
        left = wait_none_naming(out, 40)
        if left:
            self.fail("campaign-int", f"processes left: {left}")
        code2, console2, _ = run(self.campaign_command(out))
        if code2 != 0:
            self.fail("campaign-int", f"resume exited {code2}:\n{console2}")
        for problem in check_folder(self.reference, out, f"SIGINT at {delay:.2f} s"):
            self.fail("campaign-int", problem)
        log(f"campaign-int at {delay:.2f} s: exit {code}, resume exit {code2}")

    def two_campaigns(self):
        out = self.folder("two_campaigns")
        first = subprocess.Popen(self.campaign_command(out), stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                 text=True, start_new_session=True)
        fit = os.path.join(out, "fit")  # the second starts while the first's fit runs
        while not processes_naming(fit) and first.poll() is None:
            time.sleep(0.01)
        code, console, _ = run(self.campaign_command(out))
        first_console, _ = first.communicate(timeout=300)
        if first.returncode != 0:
            self.fail("two-campaigns", f"the first campaign exited {first.returncode}:\n{first_console}")
        if code != 2 or "another campaign is writing" not in console:
            self.fail("two-campaigns", f"the second exited {code}:\n{console}")
        for problem in check_folder(self.reference, out, "two campaigns"):
            self.fail("two-campaigns", problem)
        log(f"two-campaigns: second exit {code} ({console.strip().splitlines()[-1][:90]}...), first exit "
            f"{first.returncode}")

    def dem_kill(self):
        out = self.folder("dem_kill")
        for round_number in range(2):
            delay = self.random.uniform(0.1, 1.0) * self.dem_seconds
            code, _ = kill_after(self.dem_command(out), delay)
            log(f"dem-kill {round_number + 1} at {delay:.2f} s: exit {code}, left "
                f"{len(temporaries(out))} temporaries")
        planted = plant_temporaries(out, ["curve.csv", "results.h5", "frames/net_1.vtu"], kill_after.last_pid)
        code, console, _ = run(self.dem_command(out))
        if code != 0:
            self.fail("dem-kill", f"rerun exited {code}:\n{console}")
        if any(os.path.exists(p) for p in planted):
            self.fail("dem-kill", "the killed run's temporaries outlive the rerun")
        for problem in check_folder(self.dem_reference, out, "dem run after kills"):
            self.fail("dem-kill", problem)
        log(f"dem-kill: rerun exit {code}")

    def fit_kill(self):
        out = self.folder("fit_kill")
        command = self.fit_command(out, self.targets)
        for round_number in range(2):
            delay = self.random.uniform(0.1, 0.9) * self.fit_seconds
            code, _ = kill_after(command + ["--resume"] * round_number, delay)
            log(f"fit-kill {round_number + 1} at {delay:.2f} s: exit {code}, checkpoint "
                f"{'kept' if os.path.exists(os.path.join(out, 'checkpoint.json')) else 'not yet written'}")
        planted = plant_temporaries(out, ["checkpoint.json", "parameters.h5", "curves/tension_fitted.csv"],
                                    kill_after.last_pid)
        code, console, _ = run(command + ["--resume"])
        if code != 0:
            self.fail("fit-kill", f"fit --resume exited {code}:\n{console}")
        if any(os.path.exists(p) for p in planted):
            self.fail("fit-kill", "the killed fit's temporaries outlive the resume")
        for problem in check_folder(self.fit_reference, out, "fit after kills"):
            self.fail("fit-kill", problem)
        log(f"fit-kill: --resume exit {code}")

    def limited(self, case, command, out, blocks, reason, gone):
        code, console, _ = run(command, limit_blocks=blocks)
        self.check_failed_write(case, code, console, out, reason, gone)

    def check_failed_write(self, case, code, console, out, reason, gone):
        """A write that failed: exit 1 with `reason`, no temporary, none of `gone` left."""
        last = console.strip().splitlines()[-1] if console.strip() else ""
        log(f"{case}: exit {code}: {last[:160]}")
        if code in CRASH_CODES or code != 1:
            self.fail(case, f"exit {code}, expected 1: " + " | ".join(console.strip().splitlines()[-3:]))
        if reason not in console:
            self.fail(case, f"no '{reason}' in the message")
        left = temporaries(out)
        if left:
            self.fail(case, f"temporaries left: {left}")
        for name in gone:
            if os.path.exists(os.path.join(out, name)):
                self.fail(case, f"{name} is left beside a failed write")

    def file_size(self):
        out = self.folder("file_size_dem")
        # 30 KiB: the first frame (20 kB) fits, the next (38 kB) does not.
        self.limited("file-size dem run", self.dem_command(out), out, 30, "File too large",
                     ["summary.json", "results.h5", "curve.csv"])
        must_succeed(self.dem_command(out))
        for problem in check_folder(self.dem_reference, out, "dem run after the limit"):
            self.fail("file-size dem run", problem)
        out = self.folder("file_size_fit")
        # Big enough for the checkpoints, too small for parameters.h5.
        self.limited("file-size fit", self.fit_command(out, self.targets), out, 12, "File too large",
                     ["parameters.json", "parameters.h5", "fit_report.md"])
        must_succeed(self.fit_command(out, self.targets) + ["--resume"])
        for problem in check_folder(self.fit_reference, out, "fit after the limit"):
            self.fail("file-size fit", problem)
        out = self.folder("file_size_campaign")
        code, console, _ = run(self.campaign_command(out), limit_blocks=12)
        log(f"file-size campaign: exit {code}: {console.strip().splitlines()[-1][:160] if console.strip() else ''}")
        if code in CRASH_CODES or code not in (1,):
            self.fail("file-size campaign", f"exit {code}:\n{console}")
        code2, console2, _ = run(self.campaign_command(out))
        if code2 != 0:
            self.fail("file-size campaign", f"resume exited {code2}:\n{console2}")
        for problem in check_folder(self.reference, out, "campaign after the limit"):
            self.fail("file-size campaign", problem)

    def full_disk(self):
        mount = os.path.join(self.work, "full_disk")
        os.makedirs(mount, exist_ok=True)
        if os.geteuid() != 0 or subprocess.run(["mount", "-t", "tmpfs", "-o", "size=1M", "tmpfs", mount],
                                               capture_output=True).returncode != 0:
            log("full-disk: skipped (mounting a tmpfs needs root)")
            return
        try:
            # Fill all but 64 KiB: the checkpoints fit, the results do not.
            subprocess.run(["dd", "if=/dev/zero", f"of={mount}/filler", "bs=1K", "count=960"],
                           capture_output=True)
            out = os.path.join(mount, "fit")
            self.limited("full-disk fit", self.fit_command(out, self.targets), out, None,
                         "No space left on device", ["parameters.json", "parameters.h5", "fit_report.md"])
            shutil.rmtree(out, ignore_errors=True)
            out = os.path.join(mount, "dem")
            os.remove(os.path.join(mount, "filler"))
            # The run checks the free space before it starts: the disk fills up once it runs.
            process = subprocess.Popen(self.dem_command(out), stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                       text=True)
            while not os.path.isdir(out) and process.poll() is None:
                time.sleep(0.002)
            subprocess.run(["dd", "if=/dev/zero", f"of={mount}/filler", "bs=1K", "count=2048"], capture_output=True)
            console, _ = process.communicate(timeout=300)
            self.check_failed_write("full-disk dem run", process.returncode, console, out, "No space left on device",
                                    ["summary.json", "results.h5", "curve.csv"])
        finally:
            subprocess.run(["umount", mount], capture_output=True)


def main():
    if len(sys.argv) not in (4, 5):
        sys.exit(__doc__)
    dtwire, source, work = (os.path.abspath(p) for p in sys.argv[1:4])
    seed = int(sys.argv[4]) if len(sys.argv) == 5 else 53
    started = time.monotonic()
    os.makedirs(work, exist_ok=True)
    log(f"seed {seed}")
    cases = Cases(dtwire, source, work, seed)
    cases.references()
    for case in (cases.campaign_kill, cases.campaign_interrupt, cases.two_campaigns, cases.dem_kill,
                 cases.fit_kill, cases.file_size, cases.full_disk):
        case()
    log(f"{time.monotonic() - started:.0f} s in all")
    if cases.problems:
        sys.exit("FAIL:\n" + "\n".join(cases.problems))
    print("PASS")


if __name__ == "__main__":
    main()
