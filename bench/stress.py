#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Numerical stress tests too long for the test suite (issue 8), each with a pass criterion.

    python3 bench/stress.py [--nmm build/release/nmm] [--work build/stress]
                            [--only NAME[,NAME...]] [--quick]

Runs `nmm run CASE --quiet` on scenes it writes into WORK (a gmsh .geo and a case.toml each)
and checks nmm's own history.csv and summary.json against the criterion of each test:

- spin_dda: a free L-shaped DDA block (3 m^2, E = 1e9 Pa) spinning at one revolution per
  second, no loads, 100 revolutions in 1e5 steps of 1e-3 s (issue 6: area to 1e-10 per
  revolution, angular velocity to 1e-6 relative). Checked through two monitors, one at the
  centroid and one near a corner: their distance (a rigid block keeps every distance, and so
  its area) to 1e-10 relative per revolution, the kinetic energy (1/2 I omega^2) to 2e-6
  relative, no NaN in any row, and the corner back at its start after 100 revolutions within
  1e-6 m.
- spin_vem: the same block as a VEM block (recorded against the same criteria).
- drop_1e5: a 0.5 m square NMM block dropped 0.5 m onto a held NMM base
  (tests/verification/contact_test.cpp, Drop), E = 1e10 Pa, penalty 40 E, friction 30
  degrees, 1e5 steps of 1e-3 s (100 s: the drop, the bounces and 99 s at rest). Criteria:
  every row finite; the energy never grows: the kinetic energy never exceeds the work the
  loads did (history.csv load_work; strain and spring energies are >= 0), to 1e-9 of the
  largest work; the deepest penetration below 1e-3 of the block size; the block at rest on
  the base at the end (kinetic energy below 1e-9 of the work done).
- pile_1000: the jointed rock mass of bench/rock_mass.py with about 1000 DDA blocks (two
  joint sets, blocks of about 1 m^2, E = 1e10 Pa) on a DDA foundation, dynamic under gravity
  from unloaded contacts (the blocks drop into their springs), dt = 1e-3 s,
  open_close_max = 20, 300 steps (100 with --quick). Criteria: completes, every row finite,
  the deepest penetration below 1e-3 of the mean block size (1 m), and it settles: the
  kinetic energy at the end below 1e-2 of its peak.

- penalty_sweep: examples/03_block_on_incline (a block sliding down a 45 degree ramp,
  phi = 30 degrees, initial equilibrium, dt = 1e-3 s to t = 1 s) with penalty = 1, 10, 40,
  100, 1e3 and 1e4 E, at most 2500 steps each. Criteria per penalty: reaches t = 1 s; the
  distance slid within 0.1% of g (sin 45 - cos 45 tan 30) t^2 / 2 = 1.465901 m (independent
  of the penalty: the springs carry m g cos a whatever their stiffness); fewer step cuts
  than half the steps; the deepest penetration smaller than at the penalty before.

Prints one line per test with its figures and PASS or FAIL, then a Markdown table (test,
criterion, result, time) for docs/benchmarks.md, the CPU model and the load average before
and after. Exit code 1 if any test failed.
"""

import argparse
import csv
import json
import math
import os
import shutil
import subprocess
import sys
import time

from machine import cpu_model, load_average

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run_nmm(nmm, case, out):
    """Runs nmm on @p case into @p out; returns (summary, rows of history.csv, seconds)."""
    if os.path.isdir(out):
        shutil.rmtree(out)
    start = time.monotonic()
    done = subprocess.run([nmm, "run", case, "-o", out, "--quiet"], stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True)
    elapsed = time.monotonic() - start
    summary_file = os.path.join(out, "summary.json")
    if not os.path.exists(summary_file):
        sys.exit("stress: %s wrote no summary.json:\n%s" % (case, done.stdout))
    with open(summary_file) as f:
        summary = json.load(f)
    with open(os.path.join(out, "history.csv")) as f:
        rows = [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]
    return summary, rows, elapsed


def all_finite(rows):
    return all(math.isfinite(v) for row in rows for v in row.values())


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)


# ------------------------------------------------------------------------- spinning block

SPIN_GEO = """// An L-shaped block of 3 m^2 (bench/stress.py)
Point(1) = {0, 0, 0}; Point(2) = {2, 0, 0}; Point(3) = {2, 1, 0};
Point(4) = {1, 1, 0}; Point(5) = {1, 2, 0}; Point(6) = {0, 2, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4};
Line(4) = {4, 5}; Line(5) = {5, 6}; Line(6) = {6, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Physical Surface("block") = {1};
"""

SPIN_CASE = """# A free block spinning at one revolution per second (bench/stress.py)
geometry = "block.geo"
[cover_mesh]
size = 0.5
[materials.block]
model = "{model}"
density = 2500.0
young = 1.0e9
poisson = 0.25
initial_angular_velocity = 6.283185307179586
[analysis]
steps = {steps}
time_step = 1.0e-3
[[monitor]]
name = "centre"
point = [0.8333333333333334, 0.8333333333333334]
[[monitor]]
name = "corner"
point = [1.99, 0.01]
[output]
every = 100000000
"""


def spin(args, model):
    revolutions = 10 if args.quick else 100
    folder = os.path.join(args.work, "spin_" + model)
    write(os.path.join(folder, "block.geo"), SPIN_GEO)
    write(os.path.join(folder, "case.toml"), SPIN_CASE.replace("{model}", model)
          .replace("{steps}", str(1000 * revolutions)))
    summary, rows, seconds = run_nmm(args.nmm, os.path.join(folder, "case.toml"),
                                     os.path.join(folder, "out"))

    def radius(row):
        return math.hypot(row["corner.x"] - row["centre.x"], row["corner.y"] - row["centre.y"])

    r0 = math.hypot(1.99 - 0.8333333333333334, 0.01 - 0.8333333333333334)
    omega = 2.0 * math.pi
    # 1/2 I omega^2 of the L block about its centroid: I = rho * polar moment (plane strain).
    polar = (2.0 * (4.0 + 1.0) / 12.0 + 2.0 * ((1 - 5 / 6) ** 2 + (0.5 - 5 / 6) ** 2)
             + 1.0 * (1.0 + 1.0) / 12.0 + 1.0 * ((0.5 - 5 / 6) ** 2 + (1.5 - 5 / 6) ** 2))
    ke0 = 0.5 * 2500.0 * polar * omega ** 2
    worst_radius = max(abs(radius(row) - r0) / r0 for row in rows) / revolutions
    worst_ke = max(abs(row["kinetic_energy"] - ke0) / ke0 for row in rows)
    last = rows[-1]
    back = math.hypot(last["corner.x"] - 1.99, last["corner.y"] - 0.01)
    finite = all_finite(rows)
    passed = (summary["status"] == "completed" and finite and worst_radius < 1e-10
              and worst_ke < 2e-6 and back < 1e-6)
    result = ("%d steps, %s; distance change %.1e per revolution, kinetic energy %.1e, corner "
              "back within %.1e m" % (len(rows), "finite" if finite else "NaN", worst_radius,
                                      worst_ke, back))
    criterion = ("%d revolutions in %d steps: centroid-corner distance 1e-10 per revolution, "
                 "kinetic energy 2e-6, back within 1e-6 m, no NaN" % (revolutions, len(rows)))
    return criterion, result, passed, seconds


# ------------------------------------------------------------------------- dropped block

DROP_GEO = """// A 0.5 m block 0.5 m above a held base (bench/stress.py)
Point(1) = {-0.5, -0.5, 0}; Point(2) = {1.5, -0.5, 0}; Point(3) = {1.5, 0, 0}; Point(4) = {-0.5, 0, 0};
Point(5) = {0.25, 0.5, 0}; Point(6) = {0.75, 0.5, 0}; Point(7) = {0.75, 1, 0}; Point(8) = {0.25, 1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, 8}; Plane Surface(2) = {2};
Physical Surface("base") = {1};
Physical Surface("block") = {2};
Physical Curve("ground") = {1};
"""

DROP_CASE = """# A block dropped on a held base, 1e5 steps (bench/stress.py)
geometry = "drop.geo"
[cover_mesh]
size = 0.125
[materials.base]
density = 2500.0
young = 1.0e10
poisson = 0.25
[materials.block]
density = 2500.0
young = 1.0e10
poisson = 0.25
[contact]
friction_angle = 30.0
[[boundary]]
curve = "ground"
fix = "xy"
[[load]]
gravity = [0.0, -9.81]
[analysis]
steps = {steps}
time_step = 1.0e-3
[[monitor]]
name = "centre"
point = [0.5, 0.75]
[output]
every = 100000000
"""


def drop(args):
    steps = 10000 if args.quick else 100000
    folder = os.path.join(args.work, "drop")
    write(os.path.join(folder, "drop.geo"), DROP_GEO)
    write(os.path.join(folder, "case.toml"), DROP_CASE.replace("{steps}", str(steps)))
    summary, rows, seconds = run_nmm(args.nmm, os.path.join(folder, "case.toml"),
                                     os.path.join(folder, "out"))
    finite = all_finite(rows)
    work = max(abs(row["load_work"]) for row in rows)
    gain = max(row["kinetic_energy"] - row["load_work"] for row in rows) / work
    deepest = max(row["max_penetration"] for row in rows)
    last = rows[-1]
    rest = last["kinetic_energy"] / work
    cuts = sum(row["step_cuts"] for row in rows)
    passed = (summary["status"] == "completed" and finite and gain < 1e-9
              and deepest < 1e-3 * 0.5 and rest < 1e-9)
    result = ("%d steps, %s, %d cuts; largest KE - work %.1e of the work, deepest penetration "
              "%.1e m, final KE %.1e of the work, centre at y = %.6f m" %
              (len(rows), "finite" if finite else "NaN", cuts, gain, deepest, rest,
               last["centre.y"]))
    criterion = ("%d steps: no NaN, kinetic energy <= work of the loads (1e-9), penetration < "
                 "1e-3 of the block, at rest at the end" % len(rows))
    return criterion, result, passed, seconds


# ------------------------------------------------------------------------- 1000-block pile

def pile(args):
    steps = 100 if args.quick else 300
    folder = os.path.join(args.work, "pile_1000")
    subprocess.run([sys.executable, os.path.join(ROOT, "bench", "rock_mass.py"), "--blocks",
                    "1000", "--model", "dda", "--out", folder, "--steps", str(steps), "--dt",
                    "1e-3", "--open-close-max", "20"], check=True, stdout=subprocess.PIPE)
    summary, rows, seconds = run_nmm(args.nmm, os.path.join(folder, "case.toml"),
                                     os.path.join(folder, "out"))
    finite = all_finite(rows)
    deepest = max(row["max_penetration"] for row in rows)
    peak = max(row["kinetic_energy"] for row in rows)
    end = rows[-1]["kinetic_energy"] / peak
    cuts = sum(row["step_cuts"] for row in rows)
    blocks = summary.get("blocks", 0)
    passed = (summary["status"] == "completed" and finite and deepest < 1e-3 and end < 1e-2)
    result = ("%d blocks, %d steps, %s, %d cuts, at most %d contacts; deepest penetration "
              "%.1e m, kinetic energy at the end %.1e of its peak (%.3g J at step %d)" %
              (blocks, len(rows), "finite" if finite else "NaN", cuts,
               max(row["contacts"] for row in rows), deepest, end, peak,
               max(range(len(rows)), key=lambda i: rows[i]["kinetic_energy"]) + 1))
    criterion = ("%d steps of 1e-3 s from unloaded contacts: completes, no NaN, penetration < "
                 "1e-3 of the block size, kinetic energy at the end < 1e-2 of its peak" % steps)
    return criterion, result, passed, seconds


# ------------------------------------------------------------------------- penalty sweep

def penalty_sweep(args):
    example = os.path.join(ROOT, "examples", "03_block_on_incline")
    exact = 0.5 * 9.81 * (math.sin(math.pi / 4) - math.cos(math.pi / 4) * math.tan(math.pi / 6))
    penalties = [1.0, 10.0, 40.0] if args.quick else [1.0, 10.0, 40.0, 100.0, 1e3, 1e4]
    parts = []
    passed = True
    seconds = 0.0
    shallower = float("inf")
    for penalty in penalties:
        folder = os.path.join(args.work, "penalty_%g" % penalty)
        os.makedirs(folder, exist_ok=True)
        shutil.copy(os.path.join(example, "incline.geo"), folder)
        with open(os.path.join(example, "case.toml")) as f:
            text = f.read()
        text = text.replace("penalty = 40.0", "penalty = %r" % penalty)
        text = text.replace("steps = 2000", "steps = 2500")
        text = text.replace("every = 50", "every = 100000000")
        write(os.path.join(folder, "case.toml"), text)
        summary, rows, elapsed = run_nmm(args.nmm, os.path.join(folder, "case.toml"),
                                         os.path.join(folder, "out"))
        seconds += elapsed
        last = rows[-1]
        slid = -(last["block.ux"] + last["block.uy"]) / math.sqrt(2.0)
        error = abs(slid - exact) / exact
        cuts = int(sum(row["step_cuts"] for row in rows))
        deepest = max(row["max_penetration"] for row in rows)
        reached = last["time"] >= 1.0 - 1e-9
        ok = (summary["status"] == "completed" and all_finite(rows) and reached and error < 1e-3
              and 2 * cuts < len(rows) and deepest < shallower)
        shallower = deepest
        passed = passed and ok
        parts.append("%g E: %s t = %.3g s in %d steps, %d cuts, %s%.1e m deep, %.0f s" %
                     (penalty, "PASS" if ok else "FAIL", last["time"], len(rows), cuts,
                      ("error %.4f%%, " % (100 * error)) if reached else "", deepest, elapsed))
        print("  penalty %s" % parts[-1], flush=True)
    criterion = ("examples/03 at penalty %s E, dt = 1e-3 s: reaches 1 s, slides the exact "
                 "1.4659 m to 0.1%%, cuts < steps / 2, penetration falls with the penalty"
                 % ", ".join("%g" % p for p in penalties))
    return criterion, "; ".join(parts), passed, seconds


TESTS = {
    "spin_dda": lambda args: spin(args, "dda"),
    "spin_vem": lambda args: spin(args, "vem"),
    "drop_1e5": drop,
    "pile_1000": pile,
    "penalty_sweep": penalty_sweep,
}


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--nmm", default=os.path.join(ROOT, "build", "release", "nmm"))
    p.add_argument("--work", default=os.path.join(ROOT, "build", "stress"))
    p.add_argument("--only", help="comma-separated tests: " + ", ".join(TESTS))
    p.add_argument("--quick", action="store_true", help="a tenth of the steps (a smoke test)")
    args = p.parse_args(argv)
    names = args.only.split(",") if args.only else list(TESTS)
    for name in names:
        if name not in TESTS:
            sys.exit("stress: no test %r (%s)" % (name, ", ".join(TESTS)))
    print("machine: %s, %d cores; load %.2f before" % (cpu_model(), os.cpu_count() or 0,
                                                      load_average()))
    table = []
    failed = 0
    for name in names:
        before = load_average()
        criterion, result, passed, seconds = TESTS[name](args)
        after = load_average()
        failed += not passed
        print("%-10s %s  %s (%.1f s, load %.2f -> %.2f)" %
              (name, "PASS" if passed else "FAIL", result, seconds, before, after), flush=True)
        table.append((name, criterion, result + (" **PASS**" if passed else " **FAIL**"),
                      seconds, before, after))
    print()
    print("| test | criterion | result | time |")
    print("| --- | --- | --- | --- |")
    for name, criterion, result, seconds, before, after in table:
        print("| %s | %s | %s | %.1f s (load %.1f-%.1f) |" % (name, criterion, result, seconds,
                                                             before, after))
    print("\nload %.2f after" % load_average())
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
