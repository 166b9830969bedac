#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Per-step cost against unknowns and against blocks, next to the bare linear-solver floor
of the same matrix measured in the same process (issue 8, item 4).

    python3 bench/scaling.py [--bench build/release/bench/bench_step] [--work build/scaling]
                             [--dofs 1e3,3e3,1e4,3e4,1e5,3e5,1e6]
                             [--order1-dofs 1e3,3e3,1e4,3e4,1e5,3e5]
                             [--blocks 100,300,1000,3000,10000] [--models dda,vem,nmm]
                             [--block-steps 100:10,300:6,1000:4,3000:3,10000:2]
                             [--fit-dofs-from 1e4] [--fit-blocks-from 100]
                             [--no-dofs] [--no-blocks] [--pictures docs/pictures] [--no-plot]
                             [--quick]

Unknowns: `bench_step ORDER DOFS --steps K --no-output --json` (bench/step_bench.cpp), one
process per point: the 4 m x 1 m clamped beam under gravity, dynamic, order-0 covers at
--dofs and order-1 covers at --order1-dofs unknowns; the first step (pattern, symbolic
analysis) is not measured, then K steps (100 at 1e3 unknowns down to 3 from 3e5), each
followed by the bare CHOLMOD numeric factorisation + solve of the matrix it ended with (a
solver of its own, analysed untimed): the floor of a step that factorises once, measured
under the same load as the step.

Blocks: the jointed rock mass of bench/rock_mass.py (as bench/block_bench.py: seed 1, the
default two joint sets, open_close_max = 20, dt = 1e-4 s, from rest under gravity) at about
--blocks rock blocks, for each of --models; `bench_step --case CASE --warmup 1 --steps K
--json`: the case read and built through the library as `nmm run` does, one step not
measured (pattern, symbolic analysis), K measured steps (--block-steps), each followed by
as many bare factorisations + solves of the matrix it ended with as it factorised. A block
step refactorises once per open-close iteration with a mode change, so its solver floor is
the bare time times the factorisations per step; the table gives both ratios.

Fits: least squares of log(time) against log(unknowns) (points from --fit-dofs-from) or
log(blocks) (from --fit-blocks-from), for the step and for its floor.

Prints Markdown tables (for docs/benchmarks.md), writes WORK/scaling_dofs.tsv and
WORK/scaling_blocks.tsv (one block per series) with their fitted lines (WORK/*_fits.tsv)
for bench/scaling.gp, and draws PICTURES/scaling_dofs.png and scaling_blocks.png. Every
point records the 1-minute load average before and after it: on the shared 2-core machine
absolute times follow the load, the step / floor ratios much less. The whole took 34
minutes at a load of 5 on the 2 cores (the unknowns 2.6 minutes at load 2-5, the three
10,000-block points about 20 minutes; --blocks 100,300,1000,3000 leaves those out);
--quick: 1e3..1e5 unknowns and 100..1000 blocks, about 2 minutes.
"""

import argparse
import json
import os
import subprocess
import sys
import time

from figures import gnuplot, power_law
from machine import cpu_model, load_average

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def beam_steps(dofs):
    """Measured steps per point: enough for about 0.3 s of steps at small sizes."""
    for limit, steps in ((2e3, 100), (5e3, 50), (2e4, 20), (5e4, 10), (2e5, 5)):
        if dofs < limit:
            return steps
    return 3


def parse_steps(text):
    return {int(float(size)): int(count) for size, count in
            (item.split(":") for item in text.split(",") if item)}


def run_bench(command, who):
    """Runs bench_step and returns its JSON line as a dict."""
    done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    rows = [json.loads(line) for line in done.stdout.splitlines() if line.startswith("{")]
    if done.returncode != 0 or len(rows) != 1:
        sys.exit("scaling: %s (%s) failed:\n%s" % (" ".join(command), who, done.stdout))
    return rows[0]


def with_floor(row, x, series):
    """Adds the fields the tables and the plot need."""
    row["x"] = x
    row["series"] = series
    row["floor"] = row["bare_seconds"] * max(row["factorizations_per_step"], 1.0)
    return row


def dofs_points(args):
    rows = []
    for order, sizes in ((0, args.dofs), (1, args.order1_dofs)):
        for dofs in sizes:
            command = [args.bench, str(order), "%g" % dofs, "--steps", str(beam_steps(dofs)),
                       "--no-output", "--json"]
            row = with_floor(run_bench(command, "order %d, %g unknowns" % (order, dofs)), None,
                             "order %d" % order)
            row["x"] = row["unknowns"]
            rows.append(row)
            print_dofs_table(rows[-1:], header=len(rows) == 1)
    return rows


def block_points(args):
    rows = []
    for blocks in args.blocks:
        for model in args.models:
            folder = os.path.join(args.work, "%s_%d" % (model, blocks))
            steps = args.block_steps[blocks]
            generate = [sys.executable, os.path.join(ROOT, "bench", "rock_mass.py"),
                        "--blocks", str(blocks), "--model", model, "--out", folder,
                        "--steps", str(steps + 1), "--open-close-max", "20"]
            made = subprocess.run(generate, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                  text=True)
            if made.returncode != 0:
                sys.exit("scaling: %s failed:\n%s" % (" ".join(generate), made.stdout))
            planned = int(made.stdout.split("planned ")[1].split()[0])
            command = [args.bench, "--case", os.path.join(folder, "case.toml"), "--warmup", "1",
                       "--steps", str(steps), "--json"]
            rows.append(with_floor(run_bench(command, "%s, %d blocks" % (model, blocks)),
                                   planned, model))
            print_blocks_table(rows[-1:], header=len(rows) == 1)
    return rows


def ms(seconds):
    value = 1e3 * seconds
    if value >= 100:
        return "{:,.0f}".format(value)
    if value >= 10:
        return "%.1f" % value
    return "%.2f" % value


def print_dofs_table(rows, header=True):
    if header:
        print("| covers | unknowns | elements | steps | assembly | factorisation | solve | update "
              "| pattern | step | bare factor + solve | **step / bare** | flops | load |")
        print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for r in rows:
        p = r["parts"]
        print("| %s | {:,} | {:,} | %d | %s | %s | %s | %s | %s | %s | %s | **%.2f** | %.2g "
              "| %.1f-%.1f |".format(r["unknowns"], r["elements"])
              % (r["series"], r["steps"], ms(p["constraints"] + p["assembly"]),
                 ms(p["factorization"]), ms(p["solve"]), ms(p["update"]),
                 ms(p["pattern"] + p["analysis"]), ms(r["seconds_step"]), ms(r["bare_seconds"]),
                 r["seconds_step"] / r["bare_seconds"], r["bare_flops"], r["load_before"],
                 r["load_after"]))
    sys.stdout.flush()


def print_blocks_table(rows, header=True):
    if header:
        print("| model | blocks | unknowns | steps (cuts) | factorisations per step | detection "
              "| assembly | contact | factorisation | solve | update | step | bare factor + "
              "solve | step / bare | **step / (bare x factorisations)** | flops | load |")
        print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | "
              "--- | --- | --- | --- |")
    for r in rows:
        p = r["parts"]
        print("| %s | {:,} | {:,} | %d (%d) | %.1f | %s | %s | %s | %s | %s | %s | %s | %s | "
              "%.1f | **%.2f** | %.2g | %.1f-%.1f |".format(r["x"], r["unknowns"])
              % (r["series"], r["steps"], r["step_cuts"], r["factorizations_per_step"],
                 ms(p["detection"]),
                 ms(p["constraints"] + p["pattern"] + p["assembly"]), ms(p["contact"]),
                 ms(p["analysis"] + p["factorization"]), ms(p["solve"]), ms(p["update"]),
                 ms(r["seconds_step"]), ms(r["bare_seconds"]),
                 r["seconds_step"] / r["bare_seconds"], r["seconds_step"] / r["floor"],
                 r["bare_flops"], r["load_before"], r["load_after"]))
    sys.stdout.flush()


def series_of(rows):
    names = []
    for r in rows:
        if r["series"] not in names:
            names.append(r["series"])
    return names


def fits(rows, fit_from, quantities):
    """Per series and quantity (a key of the rows, or a function of a row): (exponent,
    coefficient, lowest x, highest x, points) over the rows with x >= fit_from."""
    out = []
    for name in series_of(rows):
        used = [r for r in rows if r["series"] == name and r["x"] >= fit_from]
        xs = [r["x"] for r in used]
        for label, value in quantities:
            ys = [value(r) for r in used]
            exponent, coefficient = power_law(xs, ys)
            out.append((name, label, exponent, coefficient, min(xs, default=0),
                        max(xs, default=0), len(used)))
    return out


def print_fits(fitted, variable):
    print("| series | quantity | points | %s from | exponent p (quantity ~ %s^p) |"
          % (variable, variable))
    print("| --- | --- | --- | --- | --- |")
    for name, label, exponent, _, lo, _, n in fitted:
        print("| %s | %s | %d | {:,} | %.2f |".format(lo) % (name, label, n, exponent))
    sys.stdout.flush()


def write_tsv(rows, fitted, path, plotted, variable, floor_label):
    """The points, one block per series (first line: the column titles), and the fitted
    lines of the @p plotted quantities in PATH_fits.tsv, one block of two points each."""
    with open(path, "w") as f:
        f.write("# written by bench/scaling.py; columns: x, step (s), floor (s), step / floor, "
                "bare factor + solve (s), factorisations per step, unknowns\n")
        for i, name in enumerate(series_of(rows)):
            f.write("\n\n" if i else "")
            f.write("x\t%s step\t%s %s\t%s\tbare\tfactorisations\tunknowns\n"
                    % (name, name, floor_label, name))
            for r in rows:
                if r["series"] == name:
                    f.write("%.6g\t%.6g\t%.6g\t%.6g\t%.6g\t%.6g\t%d\n"
                            % (r["x"], r["seconds_step"], r["floor"], r["seconds_step"] / r["floor"],
                               r["bare_seconds"], r["factorizations_per_step"], r["unknowns"]))
    fits_path = path.replace(".tsv", "_fits.tsv")
    blocks = 0
    with open(fits_path, "w") as f:
        for name, label, exponent, coefficient, lo, hi, n in fitted:
            if label not in plotted or n < 2:
                continue
            f.write("\n\n" if blocks else "")
            f.write("x\t%s %s ~ %s^%.2f\n" % (name, label, variable, exponent))
            for x in (lo, hi):
                f.write("%.6g\t%.6g\n" % (x, coefficient * x ** exponent))
            blocks += 1
    return fits_path, len(series_of(rows)), blocks


def plot(args, rows, fitted, name, title, xlabel, variable, floor_label, plotted):
    path = os.path.join(args.work, "scaling_%s.tsv" % name)
    fits_path, n_series, n_fits = write_tsv(rows, fitted, path, plotted, variable, floor_label)
    if args.no_plot:
        return
    png = os.path.join(args.pictures, "scaling_%s.png" % name)
    gnuplot(os.path.join(ROOT, "bench", "scaling.gp"),
            ["data='%s'" % path, "fits='%s'" % fits_path, "nseries=%d" % n_series,
             "nfits=%d" % n_fits, "png='%s'" % png, "plot_title='%s'" % title,
             "xlabel='%s'" % xlabel, "floor_label='%s'" % floor_label], png, "scaling")


def sizes(text):
    return [float(s) for s in text.split(",") if s]


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--bench", default=os.path.join(ROOT, "build", "release", "bench",
                                                   "bench_step"))
    p.add_argument("--nmm", default=os.path.join(ROOT, "build", "release", "nmm"),
                   help="only for its --version (BLAS) line")
    p.add_argument("--work", default=os.path.join(ROOT, "build", "scaling"))
    p.add_argument("--dofs", type=sizes, default=sizes("1e3,3e3,1e4,3e4,1e5,3e5,1e6"))
    p.add_argument("--order1-dofs", type=sizes, default=sizes("1e3,3e3,1e4,3e4,1e5,3e5"))
    p.add_argument("--blocks", type=lambda t: [int(x) for x in sizes(t)],
                   default=[100, 300, 1000, 3000, 10000])
    p.add_argument("--models", type=lambda t: [m for m in t.split(",") if m],
                   default=["dda", "vem", "nmm"])
    p.add_argument("--block-steps", type=parse_steps,
                   default=parse_steps("100:10,300:6,1000:4,3000:3,10000:2"),
                   help="measured steps per block count, BLOCKS:STEPS,... (after one more)")
    p.add_argument("--fit-dofs-from", type=float, default=1e4)
    p.add_argument("--fit-blocks-from", type=float, default=100)
    p.add_argument("--no-dofs", action="store_true")
    p.add_argument("--no-blocks", action="store_true")
    p.add_argument("--pictures", default=os.path.join(ROOT, "docs", "pictures"))
    p.add_argument("--no-plot", action="store_true")
    p.add_argument("--quick", action="store_true",
                   help="1e3..1e5 unknowns, 100..1000 blocks (about 2 minutes)")
    args = p.parse_args(argv)
    if args.quick:
        args.dofs = [d for d in args.dofs if d <= 1e5]
        args.order1_dofs = [d for d in args.order1_dofs if d <= 1e5]
        args.blocks = [b for b in args.blocks if b <= 1000]
    for blocks in args.blocks:
        if blocks not in args.block_steps:
            sys.exit("scaling: no step count for %d blocks in --block-steps" % blocks)
    if not os.path.exists(args.bench):
        sys.exit("scaling: no %s; build it with `bash scripts/build.sh release`" % args.bench)
    args.work = os.path.abspath(args.work)
    os.makedirs(args.work, exist_ok=True)
    version = []
    if os.path.exists(args.nmm):
        version = subprocess.run([args.nmm, "--version"], stdout=subprocess.PIPE,
                                 text=True).stdout.splitlines()
    blas = [line.split(None, 1)[1] for line in version if line.strip().startswith("BLAS")]
    print("scaling: %s; %d cores; %s; BLAS %s; %s; load %.2f" % (
        cpu_model(), os.cpu_count(), version[0] if version else "nmm",
        blas[0] if blas else "?", time.strftime("%Y-%m-%d %H:%M"), load_average()))
    print("  times in ms per step, means over the measured steps; bare: CHOLMOD numeric "
          "factorisation + solve of the matrix each step ended with, right after it; load: "
          "1-minute load average before-after the point")
    start = time.monotonic()
    dofs_rows, block_rows = [], []
    if not args.no_dofs:
        print("\n== per-step cost against unknowns (bench_step, clamped beam)\n")
        dofs_rows = dofs_points(args)
    if not args.no_blocks:
        print("\n== per-step cost against blocks (bench_step --case, bench/rock_mass.py)\n")
        block_rows = block_points(args)
    step = ("step", lambda r: r["seconds_step"])
    if dofs_rows:
        fitted = fits(dofs_rows, args.fit_dofs_from, [step, ("bare factor + solve",
                                                             lambda r: r["floor"])])
        print("\n### Unknowns\n")
        print_dofs_table(dofs_rows)
        print()
        print_fits(fitted, "unknowns")
        plot(args, dofs_rows, fitted, "dofs", "Clamped beam: wall time per step against unknowns "
             "(bench/scaling.py)", "unknowns", "unknowns", "bare factor + solve",
             ("step", "bare factor + solve"))
    if block_rows:
        floor = "bare x factorisations"
        fitted = fits(block_rows, args.fit_blocks_from,
                      [step, (floor, lambda r: r["floor"]),
                       ("bare factor + solve", lambda r: r["bare_seconds"]),
                       ("factorisations per step", lambda r: r["factorizations_per_step"]),
                       ("unknowns", lambda r: r["unknowns"])])
        print("\n### Blocks\n")
        print_blocks_table(block_rows)
        print()
        print_fits(fitted, "blocks")
        plot(args, block_rows, fitted, "blocks", "Jointed rock mass: wall time per step against "
             "blocks (bench/scaling.py)", "rock blocks", "blocks", floor, ("step", floor))
    print("\nscaling: %.0f s; load %.2f" % (time.monotonic() - start, load_average()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
