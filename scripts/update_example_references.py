#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Writes tests/regression/data/example_references.json: what each bundled example gives
when run for its first few steps (`nmm run CASE --steps N`), for the regression test
`ExampleReference.*` (tests/regression/example_references_test.cpp), which runs the same
and compares.

Run it after a change that is meant to change results, from the repository root:

    python3 scripts/update_example_references.py [path/to/nmm]

and say in the commit which examples moved and why. The list of cases is here (EXAMPLES):
a case that does not complete its steps is refused, so that no failure is stored as the
reference. An entry may change its case for the run, as a list of (text, replacement) pairs
applied to the case file, each text found exactly once; the edited case is written beside a
copy of the example's geometry. Examples 05 and 06 run that way on a cover mesh four times
coarser than theirs (one step of their fine meshes takes 6-12 s; their right answers are
checked by the slow tests against closed forms).
"""

import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "tests", "regression", "data", "example_references.json")

# (case file under examples/, steps[, edits]): about a second of run each at most.
COARSE = [("size = 0.01 ", "size = 0.04 ")]  # 05 and 06: a cover size four times theirs
EXAMPLES = [
    ("01_cantilever/case.toml", 1),
    ("02_jointed_slope/case.toml", 5),
    ("03_block_on_incline/case.toml", 50),
    ("04_dam_on_jointed_foundation/case.toml", 12),
    ("05_plate_with_hole/case.toml", 1, COARSE),
    ("06_plate_with_crack/case.toml", 1, COARSE),
    ("07_gravity_column/case.toml", 1),
    ("08_multi_block_slope/case.toml", 50),
    ("09_block_arch/case.toml", 30),
    ("10_rotating_triangle/case.toml", 5),
    ("10_rotating_triangle/case_vem.toml", 5),
    ("11_block_on_ramp/case_phi30.toml", 10),
    ("11_block_on_ramp/case_static_phi70.toml", 10),
    ("12_tunnel_36_blocks/case_phi30.toml", 10),
    ("12_tunnel_36_blocks/case_phi0.toml", 10),
    ("13_block_wall_70/case.toml", 20),
    ("13_block_wall_70/case_vem.toml", 20),
    ("14_single_joint_in_triangle/case.toml", 50),
    ("15_circular_sliding/case.toml", 20),
    ("16_jointed_double_cantilever/case.toml", 5),
    ("17_hertz_contact/case.toml", 1),
    ("18_road_cut_joint_sets/case.toml", 50),
    ("19_bolted_tunnel_stages/case.toml", 30),
]


def blas_environment():
    """OpenBLAS's Haswell kernels on any CPU with AVX2, as the test uses
    (tests/regression/example_references_test.cpp says why)."""
    env = dict(os.environ)
    with open("/proc/cpuinfo", encoding="utf-8") as f:
        if " avx2" in f.read():
            env["OPENBLAS_CORETYPE"] = "Haswell"
    return env


def edited_case(case, edits, folder):
    """The example's case with `edits` applied, written into `folder` with its geometry."""
    path = os.path.join(ROOT, "examples", case)
    with open(path, encoding="utf-8") as f:
        text = f.read()
    for old, new in edits:
        if text.count(old) != 1:
            sys.exit(f"{case}: '{old}' is not in the case exactly once")
        text = text.replace(old, new)
    geometry = re.search(r'^geometry\s*=\s*"([^"]+)"', text, re.MULTILINE).group(1)
    os.makedirs(folder, exist_ok=True)
    shutil.copy(os.path.join(os.path.dirname(path), geometry), folder)
    edited = os.path.join(folder, os.path.basename(case))
    with open(edited, "w", encoding="utf-8") as f:
        f.write(text)
    return edited


def run(nmm, case, steps, edits, out):
    path = os.path.join(ROOT, "examples", case)
    if edits:
        path = edited_case(case, edits, out + "-case")
    done = subprocess.run([nmm, "run", path, "--steps", str(steps), "-o", out, "--quiet"],
                          capture_output=True, text=True, check=False, env=blas_environment())
    with open(os.path.join(out, "summary.json"), encoding="utf-8") as f:
        summary = json.load(f)
    if done.returncode != 0 or summary["status"] != "completed" or summary["steps"] != steps:
        sys.exit(f"{case}: did not complete {steps} steps (exit {done.returncode}): "
                 f"{summary['status']}")
    reference = {"case": case, "steps": steps}
    if edits:
        reference["edits"] = [list(edit) for edit in edits]
    reference.update({
        "time": summary["time"],
        "step_cuts": summary["step_cuts"],
        "max_penetration": summary.get("max_penetration", 0.0),
        "monitors": summary["monitors"],
    })
    return reference


def main():
    nmm = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build", "release", "nmm")
    references = []
    with tempfile.TemporaryDirectory() as tmp:
        for k, (case, steps, *edits) in enumerate(EXAMPLES):
            references.append(run(nmm, case, steps, edits[0] if edits else [],
                                  os.path.join(tmp, str(k))))
            print(f"{case}: {steps} steps, {references[-1]['step_cuts']} cuts")
    os.makedirs(os.path.dirname(OUT), exist_ok=True)
    with open(OUT, "w", encoding="utf-8") as f:
        json.dump({"generated_by": "scripts/update_example_references.py",
                   "examples": references}, f, indent=1)
        f.write("\n")
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
