#!/usr/bin/env python3
"""Writes macro3d_fit.toml and macro3d_coupled_fit.toml here: the fit (3) of macro_fit.toml
with law "macro3d" instead of "thesis", plus the moment hardening apart from the axial one
(moment_hardening_ratio), without and with the N-dependent bending stiffness
(bending_axial_coupling = 1, the geometric value; reference_length_m = 0.06 from the thesis file).

The mapping subtlety (README.md here): the FE paths with rotation hold the CENTRELINE elongation
u; the law's axial displacement is what a DEM bond measures, the CHORD elongation
u_chord = (L + u) sinc(theta/2) - L. The uncoupled law ignores the chord shortening, so it is
replayed on the centreline path (as macro_fit.toml); the coupled law adds c theta^2 = L theta^2/24
to the chord elongation, so it is replayed on the chord path, which law_replay (piecewise linear
waypoints) follows through sub-waypoints every 0.25 deg (interpolation error < 1.2e-8 m, 0.15 N).
Run from this folder: python3 make_macro3d_fits.py
"""
import math
import pathlib

HERE = pathlib.Path(__file__).resolve().parent
L_MM = 60.0
STEP_DEG = 0.25

COMMON_PARAMETERS = """
[[parameter]]
name = "EA_N"
unit = "N"
initial = 1.6e7
lower = 2e6
upper = 5e7
reference = 1.6e7

[[parameter]]
name = "EI_Nm2_per_deg_convention"
unit = "N m^2/deg"
initial = 0.122
lower = 0.01
upper = 1.0
reference = 0.122

[[parameter]]
name = "N0_N"
unit = "N"
initial = 2750
lower = 300
upper = 5000
reference = 2750

[[parameter]]
name = "Nult_N"
unit = "N"
initial = 3200
lower = 1000
upper = 8000
reference = 3200

[[parameter]]
name = "Nc_N"
unit = "N"
initial = 1650
lower = 200
upper = 5000
reference = 1650

[[parameter]]
name = "m_f"
unit = "1"
initial = 0.0285
lower = 0.001
upper = 0.5
reference = 0.0285

[[parameter]]
name = "k_F"
unit = "1/m"
initial = 2.39e4
lower = 10
upper = 2e5
reference = 2.39e4

[[parameter]]
name = "k_M"
unit = "1/deg"
initial = 1
lower = 1e-3
upper = 2000
reference = 1120

# The moment capacity hardens from D sqrt(m_f) N0 to r_M D sqrt(m_f) N0 (macro3d; the thesis
# ties r_M to Nult/N0, 1.16 for the reference set). The plastic-to-elastic moment ratio of a
# round section alone is 16/(3 pi) = 1.70.
[[parameter]]
name = "moment_hardening_ratio"
unit = "1"
initial = 1.2
lower = 1.0
upper = 10.0
reference = 1.1636
"""

AXIAL = """
# ---- FE virtual experiments, axial (as macro_fit.toml) -------------------------------------
[[experiment]]
name = "tension"
target = "{targets}/tension/curve.csv"
abscissa = "displacement"
channels = ["force"]
path_displacement_mm = [0, 0.5, 18]
increments_per_leg = 200

[[experiment]]
name = "cycles"
target = "{targets}/cycles/curve.csv"
abscissa = "displacement"
channels = ["force"]
path_displacement_mm = [0, 1.5, 1.4, 4, 3.85, 8, 7.8, 10]
increments_per_leg = 60

[[experiment]]
name = "compression"
target = "{targets}/compression/curve.csv"
abscissa = "displacement"
channels = ["force"]
path_displacement_mm = [0, -0.15, -0.5]
increments_per_leg = 100
"""

BACKBONE = """
# ---- laboratory-like curve: the SW DEM backbone on the 60 mm segment ------------------------
[[experiment]]
name = "sw_dem_backbone"
target = "sw_dem_backbone.csv"
abscissa = "displacement"
channels = ["force"]
path_displacement_mm = [0, 18]
increments_per_leg = 300
"""

# name, centreline waypoints u [mm], theta [deg], increments per leg (macro_fit.toml), channels
ROTATION = [
    ("bending", [0, 0], [0, 20], 200, ["moment"]),
    ("bending_reversed", [0, 0, 0], [0, 20, -10], 150, ["moment"]),
    ("bending_cycles", [0, 0, 0, 0], [0, 12, -12, 12], 120, ["moment"]),
    ("pull_spin_20deg", [0, 0.5], [0, 20], 200, ["force", "moment"]),
    ("pull_spin_15deg", [0, 1.5], [0, 15], 200, ["force", "moment"]),
    ("pull_spin_10deg", [0, 4], [0, 10], 200, ["force", "moment"]),
    ("pull_spin_5deg", [0, 8], [0, 5], 200, ["force", "moment"]),
    ("pull_spin_unspin", [0, 1, 2], [0, 12, 0], 120, ["force", "moment"]),
]


def number(x):
    text = f"{x:.12g}"
    return "0" if text == "-0" else text


def chord_mm(u_mm, theta_deg):
    half = math.radians(theta_deg) / 2.0
    sinc = 1.0 if half == 0.0 else math.sin(half) / half
    return (L_MM + u_mm) * sinc - L_MM


def rotation_experiment(name, u, theta, increments, channels, chord):
    lines = [
        "[[experiment]]",
        f'name = "{name}"',
        f'target = "{{targets}}/{name}/curve.csv"',
        'target_columns = {force = "axial_force", rotation = {column = "rotation", factor = 2}}',
        'abscissa = "rotation"',
        "channels = [" + ", ".join(f'"{c}"' for c in channels) + "]",
    ]
    if not chord:
        if any(x != 0 for x in u):
            lines.append("path_displacement_mm = [" + ", ".join(number(x) for x in u) + "]")
        lines.append("path_rotation_deg = [" + ", ".join(number(x) for x in theta) + "]")
        lines.append(f"increments_per_leg = {increments}")
        return "\n".join(lines) + "\n"
    # Sub-waypoints every STEP_DEG along each (proportional) centreline leg, mapped to the chord;
    # the increments keep the density of macro_fit.toml (increments per original leg of the
    # longest leg's rotation).
    us, ts = [0.0], [0.0]
    longest = max(abs(b - a) for a, b in zip(theta, theta[1:]))
    per_sub_leg = max(1, math.ceil(increments * STEP_DEG / longest))
    for k in range(1, len(theta)):
        n = max(1, math.ceil(abs(theta[k] - theta[k - 1]) / STEP_DEG - 1e-9))
        for i in range(1, n + 1):
            t = i / n
            uc = u[k - 1] + (u[k] - u[k - 1]) * t
            th = theta[k - 1] + (theta[k] - theta[k - 1]) * t
            us.append(chord_mm(uc, th))
            ts.append(th)
    lines.append(f"# chord path: u_chord = (L + u) sinc(theta/2) - L on the centreline path u = {u} mm, "
                 f"theta = {theta} deg, sub-waypoints every {STEP_DEG} deg")
    lines.append("path_displacement_mm = [" + ", ".join(number(x) for x in us) + "]")
    lines.append("path_rotation_deg = [" + ", ".join(number(x) for x in ts) + "]")
    lines.append(f"increments_per_leg = {per_sub_leg}")
    return "\n".join(lines) + "\n"


def write(path, coupled):
    title = ("macro3d with the N-dependent bending stiffness (bending_axial_coupling = 1, chord paths)"
             if coupled else "macro3d without the bending-axial coupling (centreline paths)")
    head = f"""# GENERATED by make_macro3d_fits.py (edit that, then run it): fit (3) of macro_fit.toml with
# law "macro3d": {title}.
# Targets: {{targets}}/<experiment>/curve.csv, the FE runs <experiment>.prm here (README.md);
# dtwire fit {path.name} --targets <folder with the FE curves> -o OUT
title = "{title}, single wire 2.7 mm, 60 mm, 11 FE virtual experiments and the SW DEM backbone"
wire_type = "single_wire"

[simulator]
kind = "law_replay"
law = "macro3d"
fixed_parameters_file = "../data/macroelement_thesis_params.json"
fixed_parameters_section = "single_wire"
"""
    if coupled:
        head += """
[simulator.fixed]
bending_axial_coupling = 1   # c = L/24 with the thesis file's reference_length_m = 0.06
"""
    head += """
[fit]
loss = "huber"
loss_scale = 0.05
starts = 4
seed = 11
max_iterations = 60
relative_step = 1e-5
"""
    text = head + COMMON_PARAMETERS + AXIAL
    text += "\n# ---- FE virtual experiments with end rotation (half model bent about its chord) -------------\n"
    for name, u, theta, increments, channels in ROTATION:
        text += "\n" + rotation_experiment(name, u, theta, increments, channels, coupled)
    text += BACKBONE
    path.write_text(text)


if __name__ == "__main__":
    write(HERE / "macro3d_fit.toml", coupled=False)
    write(HERE / "macro3d_coupled_fit.toml", coupled=True)
