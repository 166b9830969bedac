#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Hertz's line contact (examples/17_hertz_contact, issue 8): the error of the peak contact
pressure against wall time over a sequence of refinements, for two penalties, with the
convergence rates fitted; the table and the picture of docs/benchmarks.md, "Hertz contact".

    python3 bench/hertz.py [path/to/nmm] [--n 5 10 20 40 80] [--penalty 100 1000]
                           [--repeat 3] [--tsv FILE] [--png FILE]

Refinement n is the number of boundary edges across Hertz's half-width a in the contact zone
(the `n = ...;` line of examples/17_hertz_contact/hertz.geo): the spacing there is a / n,
and the mesh grows from it by the same factor everywhere else. Each run is the example's
case with `n` and `[analysis] penalty` replaced, in a temporary folder; the fastest of
`--repeat` wall times (summary.json `wall_seconds`: reading, meshing, the step, the output)
is kept. The rates are least-squares slopes of log |error| against log n and against log
wall time, over the runs of one penalty. The picture needs gnuplot (bench/hertz.gp).
"""

import argparse
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXAMPLE = os.path.join(ROOT, "examples", "17_hertz_contact")
sys.path.insert(0, EXAMPLE)
import hertz_pressure  # noqa: E402  (examples/17_hertz_contact/hertz_pressure.py)


def slope(xs, ys):
    """Least-squares slope of ys against xs."""
    n = len(xs)
    mx = sum(xs) / n
    my = sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx if sxx > 0 else float("nan")


def run_case(nmm, n, penalty, repeat, scratch):
    folder = os.path.join(scratch, "n%g_p%g" % (n, penalty))
    os.makedirs(folder)
    with open(os.path.join(EXAMPLE, "hertz.geo"), encoding="utf-8") as f:
        geo, count = re.subn(r"^n = [^;]*;", "n = %g;" % n, f.read(), count=1, flags=re.M)
    if count != 1:
        sys.exit("hertz.geo has no `n = ...;` line")
    with open(os.path.join(folder, "hertz.geo"), "w", encoding="utf-8") as f:
        f.write(geo)
    with open(os.path.join(EXAMPLE, "case.toml"), encoding="utf-8") as f:
        case, count = re.subn(r"^penalty = [^#\n]*", "penalty = %g " % penalty, f.read(),
                              count=1, flags=re.M)
    if count != 1:
        sys.exit("case.toml has no `penalty = ...` line")
    case_file = os.path.join(folder, "case.toml")
    with open(case_file, "w", encoding="utf-8") as f:
        f.write(case)
    closed_form = hertz_pressure.hertz(case_file)
    best = None
    for _ in range(repeat):
        out = os.path.join(folder, "out")
        shutil.rmtree(out, ignore_errors=True)
        result = subprocess.run([nmm, "run", case_file, "-o", out, "--quiet"],
                                capture_output=True, text=True)
        if result.returncode != 0:
            sys.exit("n = %g, penalty %g: nmm failed (%d)\n%s"
                     % (n, penalty, result.returncode, result.stderr))
        measured = hertz_pressure.measure(out, closed_form)
        if best is None or measured["wall_seconds"] < best["wall_seconds"]:
            best = measured
    best["h"] = closed_form["a"] / n
    return best


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("nmm", nargs="?", default=os.path.join(ROOT, "build", "release", "nmm"))
    parser.add_argument("--n", type=float, nargs="+", default=[5, 10, 20, 40, 80])
    parser.add_argument("--penalty", type=float, nargs="+", default=[100, 1000])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--tsv", default=os.path.join(ROOT, "build", "hertz-bench", "hertz.tsv"))
    parser.add_argument("--png", default=os.path.join(ROOT, "docs", "pictures", "hertz.png"))
    parser.add_argument("--reuse", action="store_true",
                        help="read the runs from --tsv instead of running them again")
    args = parser.parse_args()
    os.makedirs(os.path.dirname(os.path.abspath(args.tsv)), exist_ok=True)
    rows = []
    if args.reuse:
        with open(args.tsv, encoding="utf-8") as f:
            for line in list(f)[1:]:
                penalty, n, h, dofs, wall, peak, error = line.split("\t")
                rows.append((float(penalty), float(n),
                             {"h": float(h), "dofs": int(dofs), "wall_seconds": float(wall),
                              "peak": float(peak), "error": float(error)}))
    with tempfile.TemporaryDirectory() as scratch:
        for penalty in [] if args.reuse else args.penalty:
            for n in args.n:
                r = run_case(args.nmm, n, penalty, args.repeat, scratch)
                rows.append((penalty, n, r))
                print("penalty %5g E  n = %3g: h = %.3g m, %6d dofs, %7.3f s, peak %.6g Pa, "
                      "error %+.3f%%" % (penalty, n, r["h"], r["dofs"], r["wall_seconds"],
                                         r["peak"], 100 * r["error"]), flush=True)
    with open(args.tsv, "w", encoding="utf-8") as f:
        f.write("penalty\tn\th\tdofs\twall_seconds\tpeak\terror\n")
        for penalty, n, r in rows:
            f.write("%g\t%g\t%.6g\t%d\t%.6g\t%.9g\t%.6g\n"
                    % (penalty, n, r["h"], r["dofs"], r["wall_seconds"], r["peak"], r["error"]))

    print("\n| penalty | n | h (m) | unknowns | wall (s) | peak error | change from 100 E |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    first = {n: r["error"] for penalty, n, r in rows if penalty == args.penalty[0]}
    for penalty, n, r in rows:
        change = (1 + r["error"]) / (1 + first[n]) - 1 if n in first else float("nan")
        print("| %g E | %g | %.3g | %d | %.2f | %+.3f%% | %s |"
              % (penalty, n, r["h"], r["dofs"], r["wall_seconds"], 100 * r["error"],
                 "" if penalty == args.penalty[0] else "%+.3f%%" % (100 * change)))
    print()
    for penalty in args.penalty:
        own = [(n, r) for p, n, r in rows if p == penalty and r["error"] != 0]
        ns = [math.log(n) for n, r in own]
        walls = [math.log(r["wall_seconds"]) for n, r in own]
        errors = [math.log(abs(r["error"])) for n, r in own]
        pairs = ", ".join("%g-%g: %.2f" % (own[k][0], own[k + 1][0],
                                           -(errors[k + 1] - errors[k]) / (ns[k + 1] - ns[k]))
                          for k in range(len(own) - 1))
        print("penalty %g E: against Hertz, |error| ~ n^%.2f (successive refinements %s), "
              "|error| ~ wall^%.2f" % (penalty, slope(ns, errors), pairs, slope(walls, errors)))
        # The observed order of the refinements themselves (they double n): the changes
        # e(n) - e(2n) shrink like n^-q whatever limit the sequence tends to.
        changes = [(own[k][0], own[k + 1][1]["error"] - own[k][1]["error"])
                   for k in range(len(own) - 1)]
        orders = ["%g-%g-%g: %.2f" % (changes[k][0], own[k + 1][0], own[k + 2][0],
                                      math.log(abs(changes[k][1] / changes[k + 1][1]))
                                      / math.log(own[k + 1][0] / own[k][0]))
                  for k in range(len(changes) - 1) if changes[k + 1][1] != 0]
        last = own[-1][1]["error"]
        q = None
        if len(changes) >= 2 and changes[-1][1] * changes[-2][1] > 0:
            ratio = changes[-1][1] / changes[-2][1]
            if 0 < ratio < 1:
                q = ratio
        limit = last + changes[-1][1] * q / (1 - q) if q else float("nan")
        print("    observed order of the changes %s; Richardson limit of the last three "
              "%+.3f%%" % (", ".join(orders), 100 * limit))
    if shutil.which("gnuplot") and args.png:
        subprocess.run(["gnuplot", "-e", "tsv='%s'; png='%s'" % (args.tsv, args.png),
                        os.path.join(ROOT, "bench", "hertz.gp")], check=True)
        print("\nwrote %s" % args.png)


if __name__ == "__main__":
    main()
