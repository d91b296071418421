#!/usr/bin/env python3
"""The three cases of the verdict of docs/gap.md ("The verdict"), written as curve CSVs for
`dtwire gap`: a necking wire recorded by an extensometer over part of its free length (a cause
with a plausible magnitude), the same wire 30 % stronger than the model (only a rate factor
beyond its range closes the gap), and a force ripple (no effect closes it).

The wire is the selfcheck's Voce wire (2.7 mm, 250 mm between the grips, E 180 GPa,
sigma = 380 + 170 (1 - exp(-25 eps_p)) + 150 eps_p MPa on the current section, Gaussian necking
decay over 3 % of the gauge after the Considere peak, fracture at 40 % of the peak; the same
formulas as gap/src/synthetic_curves.cpp, written again here). Up to the peak force the strain
is uniform, so an extensometer over a share s of the free length sees s times the elongation;
past the peak the strain localises in the neck, inside the extensometer, which then sees all of
the further elongation (the wire outside it unloads elastically). The stronger wire has every
flow-stress term x 1.3 (same E). The ripple is 3 % of the peak over ten periods. Load noise
0.3 % of the peak.

Usage: gap_verdict_cases.py OUT_DIR [SHARE] [SEED]
Writes OUT_DIR/sim.csv (the wire over its free length), OUT_DIR/lab_extensometer_SHARE.csv
(SHARE 0.64 unless given), OUT_DIR/lab_stronger.csv and OUT_DIR/lab_ripple.csv.
"""
import math
import os
import random
import sys

GAUGE_M = 0.25
AREA_M2 = 5.7256e-6


def voce_wire(strength=1.0):
    young, rate = 180e9, 25.0
    yield_, sat, linear = 380e6 * strength, 170e6 * strength, 150e6 * strength
    neck = 0.03 * GAUGE_M
    u, f = [0.0], [0.0]
    peak_force, peak_u = 0.0, 0.0
    for k in range(4001):
        eps_p = 0.6 * (k / 4000.0) ** 2
        stress = yield_ + sat * (1.0 - math.exp(-rate * eps_p)) + linear * eps_p
        eps_true = eps_p + stress / young
        disp = (math.exp(eps_true) - 1.0) * GAUGE_M
        force = stress * AREA_M2 * math.exp(-eps_true)
        if force >= peak_force and peak_u == 0.0:
            peak_force = force
        elif peak_u == 0.0:
            peak_u = u[-1]
        if peak_u > 0.0:
            force *= math.exp(-(((disp - peak_u) / neck) ** 2))
        if force < 0.4 * peak_force:
            break
        u.append(disp)
        f.append(force)
    # Refined as the C++ model is: 600 points evenly spaced in displacement, the vertices kept.
    grid = sorted(set([u[0] + (u[-1] - u[0]) * i / 599 for i in range(600)] + u))
    refined, j = [], 1
    for x in grid:
        while j < len(u) - 1 and u[j] < x:
            j += 1
        t = (x - u[j - 1]) / (u[j] - u[j - 1]) if u[j] > u[j - 1] else 0.0
        refined.append(f[j - 1] + min(max(t, 0.0), 1.0) * (f[j] - f[j - 1]))
    return grid, refined


def write(path, u, f):
    with open(path, "w") as out:
        out.write("displacement_mm,force_N\n")
        for x, y in zip(u, f):
            out.write(f"{x * 1e3:.9g},{y:.9g}\n")


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    out_dir = sys.argv[1]
    share = float(sys.argv[2]) if len(sys.argv) > 2 else 0.64
    seed = int(sys.argv[3]) if len(sys.argv) > 3 else 3
    os.makedirs(out_dir, exist_ok=True)
    rng = random.Random(seed)
    u, f = voce_wire()
    write(os.path.join(out_dir, "sim.csv"), u, f)
    peak = max(range(len(f)), key=lambda i: f[i])
    noisy = lambda forces, top: [y + rng.gauss(0.0, 0.003 * top) for y in forces]  # noqa: E731
    k_outside = f[1] / u[1] / (1.0 - share)
    lab_u = [share * u[i] if i <= peak else share * u[peak] + (u[i] - u[peak]) + (f[peak] - f[i]) / k_outside
             for i in range(len(u))]
    write(os.path.join(out_dir, f"lab_extensometer_{share:g}.csv"), lab_u, noisy(f, f[peak]))
    su, sf = voce_wire(1.3)
    write(os.path.join(out_dir, "lab_stronger.csv"), su, noisy(sf, max(sf)))
    ripple = [y + 0.03 * f[peak] * math.sin(2.0 * math.pi * 10.0 * x / u[-1]) for x, y in zip(u, f)]
    write(os.path.join(out_dir, "lab_ripple.csv"), u, noisy(ripple, f[peak]))


if __name__ == "__main__":
    main()
