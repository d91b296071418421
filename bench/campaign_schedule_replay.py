#!/usr/bin/env python3
"""Replays a campaign's schedule on N cores from measured step times: the runner's old policy
(file order, any step that fits starts) against the new one (app/campaign/start_order.hpp:
highest level first, a step waiting for cores is overtaken only by a step whose predicted time
ends before the waiting step's cores are predicted free). The graph comes from the campaign's
Snakefile (`dtwire campaign ... --snakefile F`: a rule waits for steps/<step>/command.txt).
usage: bench/campaign_schedule_replay.py SNAKEFILE ACTUAL_STATE.json [PREDICTED_STATE.json]
The predicted times (an earlier run's) default to the actual ones; a fresh folder has none."""
import json, re, sys

snake, actual_file = sys.argv[1], sys.argv[2]
predicted_file = sys.argv[3] if len(sys.argv) > 3 else actual_file
steps, waits, threads = [], [], []
for block in re.split(r"\nrule ", open(snake).read())[1:]:
    name = block.split(":", 1)[0]
    if name.startswith("dtwire_"):
        continue
    m = re.search(r"threads: (\d+)", block)
    steps.append(name)
    waits.append(re.findall(r'/steps/([^/]+)/command\.txt"', block.split("output:")[0]))
    threads.append(int(m.group(1)) if m else 1)
index = {s: i for i, s in enumerate(steps)}
waits = [[index[d] for d in w] for w in waits]
n = len(steps)
actual = [json.load(open(actual_file))[s]["seconds"] for s in steps]
predicted_state = json.load(open(predicted_file))
predicted = [predicted_state[s]["seconds"] if predicted_state.get(s, {}).get("status") == "done" else None for s in steps]


def levels(times):
    chain = list(times)
    for i in reversed(range(n)):
        for j in waits[i]:
            chain[j] = max(chain[j], times[j] + chain[i])
    return chain


def simulate(jobs, policy, prediction):
    cores = [min(t, jobs) for t in threads]
    order = list(range(n))
    if policy == "new":
        known = [p for p in prediction if p is not None]
        fill = sum(known) / len(known) if known else 1.0
        lv = levels([p if p is not None else fill for p in prediction])
        order.sort(key=lambda i: -lv[i])
    start, end = [None] * n, [None] * n
    t, running = 0.0, []
    while None in end:
        free = jobs - sum(cores[r] for r in running)
        reserved, reservation = False, None
        for i in order:
            if start[i] is not None or not all(end[j] is not None for j in waits[i]):
                continue
            fits = not running or cores[i] <= free
            if policy == "old":
                if fits:
                    start[i] = t; running.append(i); free -= cores[i]
                continue
            if not reserved and not fits:
                reserved = True
                rem = []
                for r in running:
                    p = prediction[r]
                    rem.append(((start[r] + p - t) if p is not None and start[r] + p > t else None, cores[r]))
                rem.sort(key=lambda x: 1e300 if x[0] is None else x[0])
                f = free
                for r_end, c in rem:
                    if r_end is None:
                        break
                    f += c
                    if f >= cores[i]:
                        reservation = r_end
                        break
                continue
            if not fits:
                continue
            if reserved and not (reservation is not None and prediction[i] is not None and prediction[i] <= reservation):
                continue
            start[i] = t; running.append(i); free -= cores[i]
        t = min(start[r] + actual[r] for r in running)
        for r in list(running):
            if start[r] + actual[r] <= t:
                end[r] = t; running.remove(r)
    return max(end) / 60.0, start


core_minutes = sum(a * min(c, 2) for a, c in zip(actual, threads)) / 60.0
print(f"{n} steps, {sum(actual) / 60:.1f} min of step time, {core_minutes:.1f} core-min on 2 cores")
for jobs in (2, 4, 8, 16):
    old, s_old = simulate(jobs, "old", predicted)
    fresh, s_fresh = simulate(jobs, "new", [None] * n)
    known, s_known = simulate(jobs, "new", predicted)
    i = index["dt_specimen_fit"]
    print(f"--jobs {jobs:2d}: old {old:6.1f} min | new, fresh folder {fresh:6.1f} | new, predicted times {known:6.1f}"
          f"   (dt_specimen_fit starts at {s_old[i] / 60:.1f} / {s_fresh[i] / 60:.1f} / {s_known[i] / 60:.1f} min)")
