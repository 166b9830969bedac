#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The VEM-DDA paper's Figure 7b (Luo 2021, 5.2): relative error of the distance slid per step.

    python3 examples/11_block_on_ramp/figure_7b.py [--nmm build/release/nmm]
                                                   [--work build/figure-7b]
                                                   [--dat examples/11_block_on_ramp/figure_7b.dat]
    gnuplot examples/11_block_on_ramp/figure_7b.gp      (writes docs/pictures/figure_7b.png)

Runs `nmm run` on case_phi15.toml, case_phi30.toml and case_phi40.toml of this folder, each
once with the block as a DDA block (the cases as they are) and once as a VEM block (the one
word `model` of [materials.block] changed; the case is written to WORK with the geometry's
absolute path). From each history.csv it takes the distance slid down the slope,
s = -(block.ux + block.uy) / sqrt(2) (the monitor at the block's centroid), and compares it
with the closed form (the paper's eq. 72) at the step's own time:

    s_exact = g t^2 (sin 45 - tan(phi) cos 45) / 2,  relative error = (s - s_exact) / s_exact.

Writes DAT (one row per step: step, time, then the error in percent of dda 15, vem 15, dda 30,
vem 30, dda 40, vem 40) and prints, as Markdown for the README: the errors at a few steps
beside the paper's, the step-1 error that the block's settling predicts and that of the DDA
block's six unknowns in step 1 (README, "Why the first step is off"), and every run's steps,
step cuts and wall time.
"""

import argparse
import csv
import json
import math
import os
import re
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
ANGLES = (15, 30, 40)
MODELS = ("dda", "vem")
G = 9.8
SLOPE = math.radians(45.0)
# The paper's relative errors (section 5.2, text; Figure 7b itself is not available), percent:
# (first step, last step 35) per friction angle and method.
PAPER = {
    (15, "dda"): (0.65, 0.06), (15, "vem"): (0.65, 0.06),
    (30, "dda"): (2.4, 0.2), (30, "vem"): (2.4, 0.2),
    (40, "dda"): (55.0, 2.9), (40, "vem"): (37.0, 2.0),
}
# The block (README, "Assumed"): length along and thickness across the slope, m; density,
# kg/m^3; Young's modulus, Pa; contact penalty, Pa (100 E); spring length (cover size), m.
LENGTH = 0.6 * math.sqrt(2.0)
THICKNESS = 0.3 * math.sqrt(2.0)
DENSITY = 2500.0
YOUNG = 3.5e7
PENALTY = 100.0 * YOUNG
SPRING_LENGTH = 0.1


def exact_distance(phi, t):
    """The paper's eq. 72: distance slid from rest in time t, m."""
    return G * t * t * (math.sin(SLOPE) - math.tan(math.radians(phi)) * math.cos(SLOPE)) / 2.0


def settling_error(phi, dt):
    """Step-1 relative error (percent) from the block settling onto unloaded springs.

    In step 1 Shi's scheme solves (K + 2M/dt^2) d = F from rest (eq. 2.18). Across the slope,
    the block's translation v and its strain e_nn (the base at -h/2 from the centroid) meet
    the springs under the base (stiffness k in all) and the weight's component W = m g cos 45:
        m' v = -W + N,  (m' h^2/12 + E A) e_nn = -N h/2,  N = -k (v - e_nn h/2),
    with m' = 2 m / dt^2. So N = W / (1 + r), r = m' h^2/4 / (E A + m' h^2/12) + m'/k: the
    block is still compressing and its centroid still falling at the end of the step, so
    the springs carry less than the weight. Friction tan(phi) N is short by the same
    fraction, and the distance slid, s = (m g sin 45 - tan(phi) N) / m', exceeds the closed
    form by (1 - N/W) tan(phi) cos 45 / (sin 45 - tan(phi) cos 45).
    """
    area = LENGTH * THICKNESS
    inertia = 2.0 * DENSITY * area / (dt * dt)
    k = PENALTY / SPRING_LENGTH * LENGTH
    h2 = THICKNESS * THICKNESS
    r = inertia * h2 / 4.0 / (YOUNG * area + inertia * h2 / 12.0) + inertia / k
    deficit = r / (1.0 + r)
    tan_phi = math.tan(math.radians(phi))
    return 100.0 * deficit * tan_phi * math.cos(SLOPE) / (math.sin(SLOPE) - tan_phi * math.cos(SLOPE))


def solve(matrix, rhs):
    """Gaussian elimination with partial pivoting (a 6 x 6 system)."""
    n = len(rhs)
    a = [row[:] + [rhs[i]] for i, row in enumerate(matrix)]
    for c in range(n):
        pivot = max(range(c, n), key=lambda r: abs(a[r][c]))
        a[c], a[pivot] = a[pivot], a[c]
        for r in range(n):
            if r != c:
                f = a[r][c] / a[c][c]
                for j in range(c, n + 1):
                    a[r][j] -= f * a[c][j]
    return [a[i][n] / a[i][i] for i in range(n)]


def dda_first_step(phi, dt, poisson=0.3):
    """Step-1 relative error (percent) of the DDA block as nmm computes it, in closed steps.

    The block's six unknowns in axes along (s, down the slope) and across (n) it, about the
    centroid: u = u0 + a_ss s + a_sn n, v = v0 + a_ns s + a_nn n (a linear field: the DDA
    cover function, Shi's eq. 2.1 in other variables). Plane stress stiffness A B^T D B, mass
    rho A diag(1, 1, L^2/12, h^2/12, L^2/12, h^2/12) times 2/dt^2, gravity on u0 and v0.
    The edge pair under the base: two Gauss points on the part that presses (a linear gap, so
    the part ends where it crosses zero), penalty / spring length per unit length; sliding,
    with the friction tan(phi) N shared equally by the two points (by their stiffness), as
    contact/contact_modes.cpp does. Iterated to a fixed point, as the open-close iteration.
    Beyond settling_error() it has the tilt from the friction's moment about the centroid:
    at phi = 40 degrees it lifts the upper end of the base off (eccentricity tan(phi) h/2 =
    0.18 m > L/6), and the springs left on the lower part meet the strain along the slope,
    which Poisson's ratio couples to the strain across it.
    """
    area = LENGTH * THICKNESS
    mass_factor = 2.0 * DENSITY * area / (dt * dt)
    mass = [mass_factor * f for f in
            (1.0, 1.0, LENGTH**2 / 12, THICKNESS**2 / 12, LENGTH**2 / 12, THICKNESS**2 / 12)]
    c = YOUNG / (1.0 - poisson**2)
    d = [[c, c * poisson, 0.0], [c * poisson, c, 0.0], [0.0, 0.0, c * (1.0 - poisson) / 2.0]]
    b = [[0, 0, 1, 0, 0, 0], [0, 0, 0, 0, 0, 1], [0, 0, 0, 1, 1, 0]]  # e_ss, e_nn, gamma
    stiffness = [[sum(area * b[i][p] * d[i][j] * b[j][q] for i in range(3) for j in range(3))
                  + (mass[p] if p == q else 0.0) for q in range(6)] for p in range(6)]
    half_h = THICKNESS / 2.0
    across = lambda s: [0.0, 1.0, 0.0, 0.0, s, -half_h]  # v at (s, -h/2)
    along = lambda s: [1.0, 0.0, s, -half_h, 0.0, 0.0]   # u at (s, -h/2)
    tan_phi = math.tan(math.radians(phi))
    weight = DENSITY * area * G
    gravity = [weight * math.sin(SLOPE), -weight * math.cos(SLOPE), 0.0, 0.0, 0.0, 0.0]
    lo, hi, friction = -LENGTH / 2.0, LENGTH / 2.0, 0.0
    for _ in range(200):
        centre, half = (lo + hi) / 2.0, (hi - lo) / 2.0
        points = (centre - half / math.sqrt(3.0), centre + half / math.sqrt(3.0))
        spring = PENALTY / SPRING_LENGTH * half
        matrix = [row[:] for row in stiffness]
        rhs = gravity[:]
        for s in points:
            h_n, h_s = across(s), along(s)
            for p in range(6):
                rhs[p] -= friction / 2.0 * h_s[p]
                for q in range(6):
                    matrix[p][q] += spring * h_n[p] * h_n[q]
        x = solve(matrix, rhs)
        gap = lambda s: sum(h * xi for h, xi in zip(across(s), x))
        normal = sum(max(0.0, -spring * gap(s)) for s in points)
        g_up, g_down = gap(-LENGTH / 2.0), gap(LENGTH / 2.0)
        new_lo, new_hi = -LENGTH / 2.0, LENGTH / 2.0
        if g_up > 0.0 > g_down:
            new_lo = -LENGTH / 2.0 + LENGTH * g_up / (g_up - g_down)
        elif g_down > 0.0 > g_up:
            new_hi = -LENGTH / 2.0 + LENGTH * g_up / (g_up - g_down)
        done = abs(tan_phi * normal - friction) < 1e-9 * weight and (new_lo, new_hi) == (lo, hi)
        friction, lo, hi = tan_phi * normal, new_lo, new_hi
        if done:
            break
    exact = exact_distance(phi, dt)
    return 100.0 * (x[0] - exact) / exact


def case_text(phi, model, out):
    """case_phiPHI.toml with the block's model and the geometry's path set, output in out."""
    with open(os.path.join(HERE, f"case_phi{phi}.toml"), encoding="utf-8") as f:
        text = f.read()
    head, sep, rest = text.partition("[materials.block]")
    if not sep:
        sys.exit(f"case_phi{phi}.toml has no [materials.block]")
    rest, n = re.subn(r'^model = "dda"', f'model = "{model}"', rest, count=1, flags=re.M)
    if n != 1:
        sys.exit(f"case_phi{phi}.toml: no model = \"dda\" in [materials.block]")
    text = head + sep + rest
    geometry = os.path.join(HERE, "block_on_ramp.geo")
    text, n = re.subn(r'^geometry = ".*"', f'geometry = "{geometry}"', text, count=1, flags=re.M)
    if n != 1:
        sys.exit(f"case_phi{phi}.toml: no geometry key")
    return text.replace(f'dir = "out/phi{phi}"', f'dir = "{out}"')


def run(nmm, work, phi, model):
    """Runs one case; returns its history rows, summary and wall time (s) as measured here."""
    out = os.path.join(work, f"phi{phi}_{model}")
    case = os.path.join(work, f"case_phi{phi}_{model}.toml")
    with open(case, "w", encoding="utf-8") as f:
        f.write(case_text(phi, model, out))
    start = time.monotonic()
    done = subprocess.run([nmm, "run", case, "-o", out, "--quiet"], capture_output=True, text=True)
    wall = time.monotonic() - start
    if done.returncode != 0:
        sys.exit(f"nmm failed on {case} ({done.returncode}):\n{done.stdout}{done.stderr}")
    with open(os.path.join(out, "summary.json"), encoding="utf-8") as f:
        summary = json.load(f)
    with open(os.path.join(out, "history.csv"), encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    return rows, summary, wall


def errors(rows, phi):
    """(step, time, relative error in percent) for every step of a history."""
    result = []
    for row in rows:
        t = float(row["time"])
        s = -(float(row["block.ux"]) + float(row["block.uy"])) / math.sqrt(2.0)
        exact = exact_distance(phi, t)
        result.append((int(row["step"]), t, 100.0 * (s - exact) / exact))
    return result


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--nmm", default=os.path.join(ROOT, "build", "release", "nmm"))
    parser.add_argument("--work", default=os.path.join(ROOT, "build", "figure-7b"))
    parser.add_argument("--dat", default=os.path.join(HERE, "figure_7b.dat"))
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    nmm = os.path.abspath(args.nmm)

    table = {}
    runs = []
    for phi in ANGLES:
        for model in MODELS:
            rows, summary, wall = run(nmm, os.path.abspath(args.work), phi, model)
            table[(phi, model)] = errors(rows, phi)
            runs.append((phi, model, summary["steps"], summary["step_cuts"],
                         summary["wall_seconds"], wall))

    # Figure 7b compares step by step; a cut step would shift the times, so the rows are
    # written only while every run is on the 0.02 s steps.
    reference = table[(ANGLES[0], MODELS[0])]
    with open(args.dat, "w", encoding="utf-8") as f:
        f.write("# Luo 2021, 5.2, Figure 7b: relative error of the distance slid, percent, "
                "(s - s_exact) / s_exact\n")
        f.write("# written by examples/11_block_on_ramp/figure_7b.py; plotted by figure_7b.gp\n")
        f.write("# step\ttime\t" + "\t".join(f"{m}{p}" for p in ANGLES for m in MODELS) + "\n")
        for k, (step, t, _) in enumerate(reference):
            values = []
            for phi in ANGLES:
                for model in MODELS:
                    series = table[(phi, model)]
                    if k >= len(series) or abs(series[k][1] - t) > 1e-9:
                        sys.exit(f"phi {phi} {model}: step {step} is not at t = {t} s (cut steps)")
                    values.append(f"{series[k][2]:.6g}")
            f.write(f"{step}\t{t:.6g}\t" + "\t".join(values) + "\n")

    print("| φ | method | step 1 | step 2 | step 5 | step 10 | step 20 | step 35 | paper step 1 | "
          "paper step 35 |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for phi in ANGLES:
        for model in MODELS:
            series = table[(phi, model)]
            cells = []
            for step in (1, 2, 5, 10, 20, 35):
                cells.append(f"{series[step - 1][2]:.4g}%" if step <= len(series) else "–")
            first, last = PAPER[(phi, model)]
            print(f"| {phi}° | {model.upper()} | " + " | ".join(cells) + f" | {first}% | {last}% |")
    print()
    print("Step 1 from the block's settling (settling_error()):",
          ", ".join(f"φ = {phi}°: {settling_error(phi, 0.02):.4g}%" for phi in ANGLES))
    print("Step 1 of the DDA block with tilt and lift-off (dda_first_step()):",
          ", ".join(f"φ = {phi}°: {dda_first_step(phi, 0.02):.4g}%" for phi in ANGLES))
    print()
    print("| φ | method | steps | step cuts | wall time (summary.json) | wall time (here) |")
    print("| --- | --- | --- | --- | --- | --- |")
    for phi, model, steps, cuts, wall_nmm, wall in runs:
        print(f"| {phi}° | {model.upper()} | {steps} | {cuts} | {wall_nmm:.2f} s | {wall:.2f} s |")
    print(f"\nwrote {args.dat}; load average {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
