#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Per-step time of DDA, VEM and NMM blocks on the same jointed rock mass (issue 6).

    python3 bench/block_bench.py [--nmm build/release/nmm] [--work build/block-bench]
                                 [--sizes 100,1000,10000] [--models dda,vem,nmm]
                                 [--steps 100:20,1000:5,10000:3] [--no-wall] [--no-rock-mass]
                                 [--threads N] [--solvers cholmod,pcg] [--steady F]

For every size N and model it writes the rock mass of bench/rock_mass.py (--blocks N --model M
--steps K --open-close-max 20, seed 1, default joint sets: the same joints for the three
models), runs `nmm run CASE --quiet` on it with each of --solvers ([analysis] solver; a run
with "pcg" is listed as model "dda/pcg" and so on) and reads the step times that nmm measured
(summary.json "counters", docs/output.md): the parts are laps of one clock through every
step, so they add up to the step time. Then the 70-block wall of examples/13_block_wall_70
(dda and vem, with open_close_max = 20 as the case has it, added if it does not), run to
its end time as the example does (583 steps of 0.012 s and a last one, output every 25).

Prints, per run: the steps, their cuts and factorisations, the mean time per step split into
detection (contact detection and the transfer of contact states), assembly (dof map,
pattern, element matrices and loads), contact (springs and friction loads of every
open-close iteration, and the mode decisions after every solve), factorisation (symbolic
analyses and numeric factorisations), solve, update (velocities, stresses, contact states,
geometry) and other (time step control and the energy check), and steps per second; then
the two goals of issue 6 (the wall's steps in under 0.2 s; at 10000 DDA blocks at least 20
steps per second) and by what factor they are met or missed. The table is Markdown (for
docs/benchmarks.md); WORK/block_bench.tsv holds the same figures for bench/block_bench.gp.

With --steady F, every rock mass is also run for F times its steps (the first run is then
the same case stopped by `nmm run --steps K`), and the difference of the two runs gives the
time of a step after the first K: the first step builds the sparsity pattern, analyses it
and touches every buffer for the first time, which a run of three steps counts a third
each. The goal at 10000 DDA blocks is then also judged on that steady time. The rock mass
dropped from rest stays nearly still for about 40 steps (one solve a step) and then moves
(about 14 open-close iterations a step): `--sizes 10000 --models dda --solvers pcg --no-wall
--steps 10000:40 --steady 2` times steps 41-80 (docs/benchmarks.md, "Blocks: DDA, VEM, NMM and conjugate gradients").

The machine's load changes every time: the script prints the 1-minute load average before
and after each run, and the CPU model. Times are wall-clock as nmm measures them.
"""

import argparse
import os
import shutil
import subprocess
import sys
import time

from machine import cpu_model, load_average
from nmm_run import run_nmm

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
WALL_GOAL_SECONDS = 0.2  # issue 6: the 70-block wall's 583 steps
DDA_GOAL_STEPS_PER_SECOND = 20.0  # issue 6: at 10000 DDA blocks


def parse_steps(text):
    steps = {}
    for item in text.split(","):
        size, count = item.split(":")
        steps[int(size)] = int(count)
    return steps


def run_nmm_counted(nmm, case, out, threads, extra=()):
    """run_nmm() with the closed contacts of the last step and the load before and after."""
    before = load_average()
    summary, rows, elapsed = run_nmm(nmm, case, out, "block_bench", threads, extra)
    contacts = int(rows[-1]["contacts"]) if rows else 0
    return summary, contacts, elapsed, (before, load_average())


def figures(label, kind, blocks, summary, contacts, elapsed, load):
    c = summary["counters"]
    steps = max(summary["steps"], 1)
    total = c["seconds_steps"]
    parts = {
        "detection": c["seconds_detection"],
        "assembly": c["seconds_constraints"] + c["seconds_pattern"] + c["seconds_assembly"],
        "contact": c["seconds_contact_springs"] + c["seconds_contact_modes"],
        "factorisation": c["seconds_analysis"] + c["seconds_factorization"],
        "solve": c["seconds_solve"],
        "update": c["seconds_update"],
    }
    parts["other"] = total - sum(parts.values())  # step control (the parts add up)
    return {
        "label": label,
        "kind": kind,
        "blocks": blocks,
        "status": summary["status"],
        "steps": summary["steps"],
        "cuts": summary["step_cuts"],
        "unknowns": summary["unknowns"],
        "contacts": contacts,
        "factorisations": c["factorizations"],
        "cg_per_solve": c.get("cg_iterations", 0) / max(c["solves"], 1),
        "cg_fallbacks": c.get("cg_fallbacks", 0),
        "seconds_steps": total,
        "wall_seconds": summary["wall_seconds"],
        "elapsed": elapsed,
        "per_step": {k: v / steps for k, v in parts.items()},
        "step": total / steps,
        "steps_per_second": summary["steps"] / total if total > 0 else float("nan"),
        "load": load,
    }


def steady_figures(short, long):
    """A summary-like dict of the steps @p long ran beyond @p short (the same case, the same
    first steps): its counters the differences."""
    later = dict(long)
    later["steps"] = long["steps"] - short["steps"]
    later["step_cuts"] = long["step_cuts"] - short["step_cuts"]
    later["wall_seconds"] = long["wall_seconds"] - short["wall_seconds"]
    later["counters"] = {k: v - short["counters"].get(k, 0) for k, v in long["counters"].items()
                         if isinstance(v, (int, float))}
    return later


def verdict(speed):
    """speed: achieved over wanted (> 1: faster than the goal)."""
    if speed >= 1.0:
        return "met, %.1fx faster than the goal" % speed
    return "missed, %.1fx too slow" % (1.0 / max(speed, 1e-300))


def ms(seconds):
    value = 1e3 * seconds
    if value >= 100:
        return "%.0f" % value
    if value >= 10:
        return "%.1f" % value
    return "%.2f" % value


def print_table(rows):
    print("| scene | model | blocks | unknowns | closed contacts | steps (cuts) | factorisations "
          "per step (CG iterations per solve, fallbacks) | detection | assembly | contact | factorisation | solve | update | other "
          "| **step** ms | steps/s | load |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- "
          "| --- | --- | --- |")
    for r in rows:
        p = r["per_step"]
        status = "" if r["status"] == "completed" else " (%s)" % r["status"][:60]
        factorisations = "%.1f" % (r["factorisations"] / max(r["steps"], 1))
        if "/" in r["kind"]:
            factorisations += " (%.1f, %d)" % (r["cg_per_solve"], r["cg_fallbacks"])
        print("| %s | %s | %d | %d | %d | %d (%d)%s | %s | %s | %s | %s | %s | %s | %s | %s "
              "| **%s** | %.3g | %.1f-%.1f |"
              % (r["label"], r["kind"], r["blocks"], r["unknowns"], r["contacts"], r["steps"],
                 r["cuts"], status, factorisations, ms(p["detection"]),
                 ms(p["assembly"]), ms(p["contact"]), ms(p["factorisation"]), ms(p["solve"]),
                 ms(p["update"]), ms(p["other"]), ms(r["step"]), r["steps_per_second"],
                 r["load"][0], r["load"][1]))
    sys.stdout.flush()


def write_tsv(path, rows):
    with open(path, "w") as f:
        f.write("# label\tmodel\tblocks\tunknowns\tsteps\tcuts\tfactorisations\tdetection\t"
                "assembly\tcontact\tfactorisation\tsolve\tupdate\tother\tstep\tsteps_per_second\n")
        for r in rows:
            p = r["per_step"]
            f.write("%s\t%s\t%d\t%d\t%d\t%d\t%d\t%.6g\t%.6g\t%.6g\t%.6g\t%.6g\t%.6g\t%.6g\t%.6g\t"
                    "%.6g\n" % (r["label"], r["kind"], r["blocks"], r["unknowns"], r["steps"],
                                r["cuts"], r["factorisations"], p["detection"], p["assembly"],
                                p["contact"], p["factorisation"], p["solve"], p["update"],
                                p["other"], r["step"], r["steps_per_second"]))


def kind(model, solver):
    """The model column: the model, with "/pcg" for conjugate gradients."""
    return model if solver == "cholmod" else "%s/%s" % (model, solver)


def wall_case(work, model, solver):
    """examples/13_block_wall_70 with the model and solver switched and open_close_max = 20
    added."""
    source = os.path.join(ROOT, "examples", "13_block_wall_70")
    folder = os.path.join(work, "wall70_%s" % kind(model, solver).replace("/", "_"))
    os.makedirs(folder, exist_ok=True)
    shutil.copy(os.path.join(source, "block_wall_70.geo"), folder)
    with open(os.path.join(source, "case.toml")) as f:
        lines = f.read().splitlines()
    out = []
    has_limit = any(line.startswith("open_close_max") for line in lines)
    for line in lines:
        if line.startswith("model = "):
            line = 'model = "%s"' % model
        out.append(line)
        if line.startswith("[analysis]") and not has_limit:
            out.append("open_close_max = 20   # added by bench/block_bench.py")
        if line.startswith("[analysis]") and solver != "cholmod":
            out.append('solver = "%s"   # added by bench/block_bench.py' % solver)
    case = os.path.join(folder, "case.toml")
    with open(case, "w") as f:
        f.write("\n".join(out) + "\n")
    return case, folder


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--nmm", default=os.path.join(ROOT, "build", "release", "nmm"))
    p.add_argument("--work", default=os.path.join(ROOT, "build", "block-bench"),
                   help="folder for the generated cases and their output")
    p.add_argument("--sizes", default="100,1000,10000")
    p.add_argument("--models", default="dda,vem,nmm")
    p.add_argument("--steps", default="100:20,1000:5,10000:3",
                   help="steps per size, SIZE:STEPS,... (default 100:20,1000:5,10000:3)")
    p.add_argument("--no-wall", action="store_true", help="skip the 70-block wall")
    p.add_argument("--no-rock-mass", action="store_true", help="only the 70-block wall")
    p.add_argument("--threads", type=int, help="nmm --threads (default: nmm's, the usable cores)")
    p.add_argument("--solvers", default="cholmod",
                   help="[analysis] solver of the runs, cholmod and/or pcg (default cholmod)")
    p.add_argument("--steady", type=int, default=0, metavar="F",
                   help="also run each rock mass for F times its steps and print the time of "
                        "a step after the first ones (F >= 2)")
    args = p.parse_args(argv)
    if not os.path.exists(args.nmm):
        sys.exit("block_bench: no %s; build it with `bash scripts/build.sh release`" % args.nmm)
    if args.steady == 1 or args.steady < 0:
        sys.exit("block_bench: --steady takes a factor of at least 2")
    steps = parse_steps(args.steps)
    sizes = [int(s) for s in args.sizes.split(",") if s]
    models = [m for m in args.models.split(",") if m]
    solvers = [s for s in args.solvers.split(",") if s]
    if not solvers or any(s not in ("cholmod", "pcg") for s in solvers):
        sys.exit("block_bench: --solvers takes cholmod and/or pcg")
    for size in sizes:
        if size not in steps:
            sys.exit("block_bench: no step count for size %d in --steps" % size)
    os.makedirs(args.work, exist_ok=True)
    version = subprocess.run([args.nmm, "--version"], stdout=subprocess.PIPE,
                             text=True).stdout.splitlines()
    blas = [line.split(None, 1)[1] for line in version if line.strip().startswith("BLAS")]
    print("block_bench: %s; %d cores; %s; %s; BLAS %s" % (
        cpu_model(), os.cpu_count(), version[0] if version else "nmm", time.strftime("%Y-%m-%d %H:%M"),
        blas[0] if blas else "?"))
    print("  per-step times in ms, means over the run's steps (cut tries included); "
          "load: 1-minute load average before-after the run")
    rows = []
    steady = []  # (row, steady row) of --steady
    if not args.no_rock_mass:
        for size in sizes:
            for model in models:
                for solver in solvers:
                    folder = os.path.join(args.work, "%s_%d" % (kind(model, solver).replace("/", "_"),
                                                                size))
                    generate = [sys.executable, os.path.join(ROOT, "bench", "rock_mass.py"),
                                "--blocks", str(size), "--model", model, "--out", folder,
                                "--steps", str(steps[size] * max(args.steady, 1)),
                                "--open-close-max", "20", "--solver", solver]
                    made = subprocess.run(generate, stdout=subprocess.PIPE,
                                          stderr=subprocess.STDOUT, text=True)
                    if made.returncode != 0:
                        sys.exit("block_bench: %s failed:\n%s" % (" ".join(generate), made.stdout))
                    planned = int(made.stdout.split("planned ")[1].split()[0])
                    case = os.path.join(folder, "case.toml")
                    summary, contacts, elapsed, load = run_nmm_counted(
                        args.nmm, case, os.path.join(folder, "out"), args.threads,
                        ["--steps", str(steps[size])] if args.steady else [])
                    rows.append(figures("rock mass", kind(model, solver), planned, summary,
                                        contacts, elapsed, load))
                    print_table(rows[-1:])
                    if args.steady:
                        long_summary, long_contacts, long_elapsed, long_load = run_nmm_counted(
                            args.nmm, case, os.path.join(folder, "out_steady"), args.threads)
                        later = steady_figures(summary, long_summary)
                        steady.append((rows[-1], figures(
                            "rock mass, steps %d-%d" % (summary["steps"] + 1, long_summary["steps"]),
                            kind(model, solver), planned, later, long_contacts, long_elapsed,
                            long_load)))
                        print_table([steady[-1][1]])
    if not args.no_wall:
        for model in ("dda", "vem"):
            for solver in solvers:
                case, folder = wall_case(args.work, model, solver)
                summary, contacts, elapsed, load = run_nmm_counted(
                    args.nmm, case, os.path.join(folder, "out"), args.threads)
                rows.append(figures("wall 70", kind(model, solver), 70, summary, contacts,
                                    elapsed, load))
                print_table(rows[-1:])
    print()
    print_table(rows)
    if steady:
        print()
        print("after the first steps (--steady %d: the longer run less the shorter):" % args.steady)
        print_table([later for _, later in steady])
    write_tsv(os.path.join(args.work, "block_bench.tsv"), rows + [later for _, later in steady])
    print()
    for r in rows:
        if r["label"] == "wall 70":
            print("goal: the 70-block %s wall's %d steps in under %.1f s: %.2f s of steps (%.2f s "
                  "with meshing and output): %s" % (
                      r["kind"], r["steps"], WALL_GOAL_SECONDS, r["seconds_steps"],
                      r["wall_seconds"], verdict(WALL_GOAL_SECONDS / r["seconds_steps"])))
        if r["kind"].startswith("dda") and r["blocks"] >= 9000 and r["label"] == "rock mass":
            print("goal: at %d DDA blocks at least %.0f steps/s: %.3g steps/s: %s" % (
                r["blocks"], DDA_GOAL_STEPS_PER_SECOND, r["steps_per_second"],
                verdict(r["steps_per_second"] / DDA_GOAL_STEPS_PER_SECOND)))
            for first, later in steady:
                if first is r:
                    print("      after its first %d steps (%s): %.3g steps/s: %s" % (
                        r["steps"], later["label"].split(", ")[1], later["steps_per_second"],
                        verdict(later["steps_per_second"] / DDA_GOAL_STEPS_PER_SECOND)))
    print("figures: %s" % os.path.join(args.work, "block_bench.tsv"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
