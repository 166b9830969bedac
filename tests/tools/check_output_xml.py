# SPDX-License-Identifier: MIT
"""Every file nmm writes for ParaView is well-formed XML without appended data (issue 43).

ParaView 5.11 (VTK before 9.3.1) with an expat that defers reparsing (2.6, and Debian 12's
2.5.0 since its fix of CVE-2023-52425) cannot read VTK XML files with an AppendedData
element: "not well-formed (invalid token)", for raw bytes (not XML at all) and for base64
alike (checked with Debian 12's ParaView on 2026-12-01). So each .vtu, .vtp and .pvd is
parsed here with Python's strict XML parser (xml.etree.ElementTree, expat underneath), a
VTK file must have no AppendedData, and each data array is decoded by scripts/vtk_xml.py and
checked against the sizes the file declares; each .pvd's DataSet entries must name existing
files and carry a part name.

Usage:
  check_output_xml.py --nmm NMM --examples EXAMPLES_DIR --work DIR
      runs `nmm mesh` and `nmm run` on a few examples into DIR (emptied first), then checks
      every file they wrote
  check_output_xml.py FILE_OR_DIR...
      checks the given files, and the VTK files in the given directories
Exit code 0 when every file passes, 1 otherwise (each failure is printed).
"""

import argparse
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ElementTree

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                "scripts"))
from vtk_xml import read_arrays  # noqa: E402  (scripts/vtk_xml.py)

EXTENSIONS = (".vtu", ".vtp", ".pvd")

# (command, case relative to the examples, extra arguments): the mesh files of `nmm mesh`,
# step files of one block, and step, contact and boundary files of blocks in contact (DDA
# and VEM blocks too).
RUNS = [
    ("mesh", "02_jointed_slope/case.toml", []),
    ("run", "01_cantilever/case.toml", []),
    ("run", "03_block_on_incline/case.toml", ["--steps", "3"]),
    ("run", "10_rotating_triangle/case_vem.toml", ["--steps", "2"]),
]


def check_vtk(path, root):
    """Problems of a .vtu or .vtp beyond its XML being well-formed."""
    problems = []
    appended = root.find("AppendedData")
    if appended is not None:
        problems.append("appended data (encoding %r), which ParaView 5.11 cannot read with "
                        "Debian 12's expat" % appended.get("encoding"))
    piece = root.find("./*/Piece")
    if piece is None:
        return problems + ["no Piece element"]
    counts = {"FieldData": None, "PointData": int(piece.get("NumberOfPoints", "0")),
              "Points": int(piece.get("NumberOfPoints", "0"))}
    if root.get("type") == "UnstructuredGrid":
        counts["CellData"] = int(piece.get("NumberOfCells", "0"))
    else:
        counts["CellData"] = sum(int(piece.get("NumberOf" + kind, "0"))
                                 for kind in ("Verts", "Lines", "Strips", "Polys"))
    try:
        arrays = read_arrays(path)
    except Exception as error:  # noqa: BLE001  (any failure to decode is the finding)
        return problems + ["scripts/vtk_xml.py cannot decode it: %s" % error]
    for section, count in counts.items():
        element = root.find("./*/FieldData") if section == "FieldData" else piece.find(section)
        if element is None:
            continue
        # DataArray for numbers, Array for text (type="String").
        for array in element.findall("DataArray") + element.findall("Array"):
            name = "Points" if section == "Points" else array.get("Name")
            components = int(array.get("NumberOfComponents", "1"))
            values = arrays.get(name)
            # Field data has as many tuples as each array says.
            tuples = int(array.get("NumberOfTuples", "1")) if count is None else count
            if values is None:
                problems.append("array %s not decoded" % name)
            elif len(values) != tuples * components:
                problems.append("array %s: %d values for %d tuples of %d" %
                                (name, len(values), tuples, components))
    return problems


def check_pvd(path, root):
    """Problems of a .pvd beyond its XML being well-formed."""
    problems = []
    datasets = root.findall("./Collection/DataSet")
    if not datasets:
        problems.append("no DataSet entries")
    for dataset in datasets:
        file = dataset.get("file", "")
        if not os.path.isfile(os.path.join(os.path.dirname(path), file)):
            problems.append("DataSet file %r does not exist" % file)
        if not dataset.get("name"):
            problems.append("DataSet of %r has no name" % file)
    return problems


def check(path):
    """The problems of one file (empty when it is fine)."""
    try:
        root = ElementTree.parse(path).getroot()
    except ElementTree.ParseError as error:
        return ["not well-formed XML: %s" % error]
    if root.tag != "VTKFile":
        return ["root element %s, not VTKFile" % root.tag]
    return check_pvd(path, root) if path.endswith(".pvd") else check_vtk(path, root)


def files_in(paths):
    found = []
    for path in paths:
        if os.path.isdir(path):
            for folder, _, names in sorted(os.walk(path)):
                found += [os.path.join(folder, n) for n in sorted(names) if n.endswith(EXTENSIONS)]
        else:
            found.append(path)
    return found


def run_examples(nmm, examples, work):
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    for command, case, extra in RUNS:
        out = os.path.join(work, case.replace("/", "_").replace(".toml", ""))
        argv = [nmm, command, os.path.join(examples, case), "-o", out] + extra
        if command == "run":
            argv.append("--quiet")
        result = subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                text=True, check=False)
        if result.returncode != 0:
            sys.exit("check_output_xml: %s exited with %d:\n%s" %
                     (" ".join(argv), result.returncode, result.stdout))
    return [work]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--nmm", help="the nmm executable: run the examples first")
    parser.add_argument("--examples", help="the examples folder (with --nmm)")
    parser.add_argument("--work", help="the folder for the runs' output (with --nmm)")
    parser.add_argument("paths", nargs="*", help="files or folders to check")
    args = parser.parse_args()
    paths = list(args.paths)
    if args.nmm:
        if not args.examples or not args.work:
            parser.error("--nmm needs --examples and --work")
        paths += run_examples(args.nmm, args.examples, args.work)
    files = files_in(paths)
    if not files:
        sys.exit("check_output_xml: no .vtu, .vtp or .pvd files in %s" % " ".join(paths))
    failed = 0
    kinds = {}
    for path in files:
        problems = check(path)
        kinds[os.path.splitext(path)[1]] = kinds.get(os.path.splitext(path)[1], 0) + 1
        for problem in problems:
            print("%s: %s" % (path, problem))
        failed += bool(problems)
    print("check_output_xml: %d of %d files fail (%s)" %
          (failed, len(files), ", ".join("%d %s" % (n, k) for k, n in sorted(kinds.items()))))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
