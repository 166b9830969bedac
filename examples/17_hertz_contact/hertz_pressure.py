#!/usr/bin/env python3
"""Hertz's peak pressure against nmm's (examples/17_hertz_contact/README.md).

Reads the last contacts_NNNNNN.vtp of a run (the `pressure` and `length` arrays of
docs/output.md), the case file (the two materials and the load) and the .geo (R), and prints
the closed form, the peak pressure of the run and its error, the contact half-width and the
sum of the contact forces against the load. Python 3.11 standard library only: the VTK files
are read by scripts/vtk_xml.py.

    python3 examples/17_hertz_contact/hertz_pressure.py [OUT_DIR] [--case CASE] [--profile FILE]

OUT_DIR defaults to the case's [output] dir; --profile writes x, the run's pressure and
Hertz's, one line per contact point, for gnuplot.
"""

import argparse
import glob
import json
import math
import os
import re
import sys
import tomllib

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "scripts"))
from vtk_xml import read_arrays  # noqa: E402  (scripts/vtk_xml.py: nmm's VTK files, base64 + LZ4)


def hertz(case_file):
    """Closed form of the case: R, P (per metre, whole cylinder), E*, a, p0."""
    with open(case_file, "rb") as f:
        case = tomllib.load(f)
    geometry = os.path.join(os.path.dirname(case_file), case["geometry"])
    with open(geometry) as f:
        radius = float(re.search(r"^R = ([0-9.eE+-]+);", f.read(), re.M).group(1))
    cylinder = case["materials"]["cylinder"]
    block = case["materials"]["block"]
    (load,) = [entry for entry in case["load"] if entry.get("curve") == "load"]
    # The quarter cylinder is loaded on its horizontal radius: half the load of the whole.
    force = 2.0 * load["pressure"] * radius
    compliance = sum((1.0 - m["poisson"] ** 2) / m["young"] for m in (cylinder, block))
    modulus = 1.0 / compliance  # E*, plane strain
    half_width = math.sqrt(4.0 * force * radius / (math.pi * modulus))
    peak = math.sqrt(force * modulus / (math.pi * radius))
    return {"R": radius, "P": force, "E*": modulus, "a": half_width, "p0": peak}


def measure(out_dir, closed_form):
    """The run's peak pressure, contact half-width and contact force (half model)."""
    files = sorted(glob.glob(os.path.join(out_dir, "contacts_*.vtp")))
    if not files:
        sys.exit("no contacts_*.vtp in %s: run the case first" % out_dir)
    contacts = read_arrays(files[-1], {"Points", "state", "pressure", "length"})
    closed = [k for k, state in enumerate(contacts["state"]) if state != 0]
    if not closed:
        sys.exit("%s: no closed contact" % files[-1])
    x = [contacts["Points"][3 * k] for k in closed]
    pressure = [contacts["pressure"][k] for k in closed]
    length = [contacts["length"][k] for k in closed]
    summary_file = os.path.join(out_dir, "summary.json")
    summary = json.load(open(summary_file)) if os.path.exists(summary_file) else {}
    peak = max(pressure)
    return {
        "file": files[-1],
        "peak": peak,
        "error": peak / closed_form["p0"] - 1.0,
        "half_width": max(x),
        # The springs' forces: pressure x length summed per slave edge gives its force.
        "force": sum(p * l for p, l in zip(pressure, length)),
        "wall_seconds": summary.get("wall_seconds"),
        "dofs": summary.get("dofs"),
        "profile": sorted(zip(x, pressure)),
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("out_dir", nargs="?", help="output folder of the run")
    parser.add_argument("--case", default=os.path.join(HERE, "case.toml"))
    parser.add_argument("--profile", help="write x, pressure, Hertz's pressure to this file")
    parser.add_argument("--json", action="store_true", help="print the figures as JSON")
    args = parser.parse_args()
    closed_form = hertz(args.case)
    out_dir = args.out_dir
    if out_dir is None:
        with open(args.case, "rb") as f:
            out = tomllib.load(f).get("output", {}).get("dir", "out")
        out_dir = os.path.join(os.path.dirname(os.path.abspath(args.case)), out)
    run = measure(out_dir, closed_form)
    if args.profile:
        with open(args.profile, "w") as f:
            f.write("# x (m), pressure of the run (Pa), Hertz's p0 sqrt(1 - x^2/a^2) (Pa)\n")
            for x, p in run["profile"]:
                exact = closed_form["p0"] * math.sqrt(max(0.0, 1.0 - (x / closed_form["a"]) ** 2))
                f.write("%.9g %.9g %.9g\n" % (x, p, exact))
    if args.json:
        run.pop("profile")
        print(json.dumps({"closed_form": closed_form, "run": run}, indent=1))
        return
    a = closed_form["a"]
    print("Hertz: P = %.6g N/m, E* = %.6g Pa, a = %.6g m, p0 = %.6g Pa"
          % (closed_form["P"], closed_form["E*"], a, closed_form["p0"]))
    print("run:   peak pressure %.6g Pa, error %+.3f%%; contact to x = %.6g m (a %+.2f%%); "
          "contact force %.6g N/m (P/2 %+.3f%%)"
          % (run["peak"], 100.0 * run["error"], run["half_width"],
             100.0 * (run["half_width"] / a - 1.0), run["force"],
             100.0 * (run["force"] / (0.5 * closed_form["P"]) - 1.0)))
    print("       %s" % run["file"])


if __name__ == "__main__":
    main()
