#!/usr/bin/env python3
"""A campaign interrupted by a signal to the runner's pid alone (as `kill PID` or a batch system
sends it) stops the running step's whole process tree, starts nothing new, keeps its state and
exits 128 + signal (issue 37's reliability; app/campaign/interruption.hpp).

usage: campaign_interrupt_test.py DTWIRE SOURCE_DIR WORKDIR

A two-step campaign: a 3 x 3 m punch (minutes of work) and a step that waits for it. The runner
gets SIGINT, then in a second run SIGTERM, once the punch is under way.
"""
import json
import os
import signal
import subprocess
import sys
import time


def processes_naming(argument):
    """pids of the processes with this command-line argument."""
    found = []
    for pid in os.listdir("/proc"):
        if not pid.isdigit():
            continue
        try:
            with open(f"/proc/{pid}/cmdline", "rb") as f:
                if b"\0" + argument.encode() + b"\0" in f.read():
                    found.append(int(pid))
        except OSError:
            pass
    return found


def interrupt_once(dtwire, campaign, out, signal_number):
    runner = subprocess.Popen([dtwire, "campaign", campaign, "-o", out], stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, text=True, start_new_session=True)
    punch_output = os.path.join(out, "punch")  # the punch's own command line names it
    deadline = time.monotonic() + 60
    while not [p for p in processes_naming(punch_output) if p != runner.pid]:
        if time.monotonic() > deadline or runner.poll() is not None:
            sys.exit(f"FAIL: the punch step did not start:\n{runner.communicate()[0]}")
        time.sleep(0.2)
    time.sleep(1.0)
    os.kill(runner.pid, signal_number)  # the runner alone, not its group
    try:
        console, _ = runner.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        runner.kill()
        sys.exit("FAIL: the runner did not stop within 60 s of the signal")
    problems = []
    if runner.returncode != 128 + signal_number:
        problems.append(f"exit code {runner.returncode}, expected {128 + signal_number}")
    if "campaign interrupted" not in console:
        problems.append("no 'campaign interrupted' message")
    time.sleep(0.5)
    left = processes_naming(punch_output)
    if left:
        problems.append(f"the punch step's processes still run: {left}")
        for pid in left:
            os.kill(pid, signal.SIGKILL)
    try:
        with open(os.path.join(out, "campaign_state.json")) as f:
            state = json.load(f)
    except OSError:
        state = {}
        problems.append("no campaign_state.json")
    if state.get("punch", {}).get("status") != "failed":
        problems.append(f"the punch is not recorded as failed: {state.get('punch')}")
    if "after_punch" in state:
        problems.append("the step waiting for the punch was started")
    last = console.strip().splitlines()[-1] if console.strip() else "(no console output)"
    print(f"signal {signal_number}: exit {runner.returncode}; {last}")
    return problems


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    dtwire, source, work = (os.path.abspath(p) for p in sys.argv[1:])
    os.makedirs(work, exist_ok=True)
    campaign = os.path.join(work, "campaign.toml")
    punch = os.path.join(source, "experiments/dem/punch_macro.toml")
    with open(campaign, "w") as f:
        f.write(f'''name = "interrupt"
[[step]]
name = "punch"
command = ["dem", "run", "{punch}", "--set", "dynamics.threads=1", "--no-frames", "-q", "-o", "{{out}}/punch"]
outputs = ["{{out}}/punch/curve.csv"]

[[step]]
name = "after_punch"
command = ["dem", "plot-punch", "{{out}}/punch.png", "{{out}}/punch/curve.csv"]
inputs = ["{{out}}/punch/curve.csv"]
outputs = ["{{out}}/punch.png"]
''')
    problems = []
    for number in (signal.SIGINT, signal.SIGTERM):
        out = os.path.join(work, f"out_{number}")
        subprocess.run(["rm", "-rf", out], check=True)
        problems += [f"signal {number}: {p}" for p in interrupt_once(dtwire, campaign, out, number)]
    if problems:
        sys.exit("FAIL:\n" + "\n".join(problems))
    print("PASS")


if __name__ == "__main__":
    main()
