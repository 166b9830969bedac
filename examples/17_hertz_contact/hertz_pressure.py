#!/usr/bin/env python3
"""Hertz's peak pressure against nmm's (examples/17_hertz_contact/README.md).

Reads the last contacts_NNNNNN.vtp of a run (the `pressure` and `length` arrays of
docs/output.md), the case file (the two materials and the load) and the .geo (R), and prints
the closed form, the peak pressure of the run and its error, the contact half-width and the
sum of the contact forces against the load. Python 3.11 standard library only: the VTK files
are LZ4-compressed, and the LZ4 block format is decoded here.

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
import struct
import sys
import tomllib

HERE = os.path.dirname(os.path.abspath(__file__))


def lz4_block(source, size):
    """Decodes one LZ4 block (the format of the lz4 library's LZ4_compress_default)."""
    out = bytearray()
    i = 0

    def length(nibble):
        """A length from its token nibble: 15 goes on in bytes until one below 255."""
        nonlocal i
        if nibble == 15:
            while True:
                extra = source[i]
                i += 1
                nibble += extra
                if extra != 255:
                    break
        return nibble

    while i < len(source):
        token = source[i]
        i += 1
        literals = length(token >> 4)
        out += source[i:i + literals]
        i += literals
        if i >= len(source):  # the last sequence has literals only
            break
        offset = source[i] | (source[i + 1] << 8)
        i += 2
        match = length(token & 15) + 4
        start = len(out) - offset
        for k in range(match):  # byte by byte: a match may overlap what it copies
            out.append(out[start + k])
    if len(out) != size:
        raise ValueError("LZ4 block decoded to %d bytes, expected %d" % (len(out), size))
    return bytes(out)


def read_vtk(path):
    """The data arrays of a VTK XML file written by nmm (appended raw, LZ4), by name."""
    with open(path, "rb") as f:
        data = f.read()
    head, _, raw = data.partition(b'<AppendedData encoding="raw">')
    raw = raw[raw.index(b"_") + 1:]
    text = head.decode()
    header = "Q" if 'header_type="UInt64"' in text else "I"
    width = struct.calcsize(header)
    types = {"Float64": "d", "Float32": "f", "Int32": "i", "Int64": "q", "UInt8": "B",
             "Int8": "b", "UInt32": "I", "UInt64": "Q"}
    arrays = {}
    for element in re.finditer(r"<(Points|PointData|CellData|Verts|FieldData)>|<DataArray ([^>]*)>",
                               text):
        if element.group(1):
            section = element.group(1)
            continue
        attributes = dict(re.findall(r'(\w+)="([^"]*)"', element.group(2)))
        offset = int(attributes["offset"])
        blocks, block_size, last_size = struct.unpack_from("<3" + header, raw, offset)
        sizes = struct.unpack_from("<%d%s" % (blocks, header), raw, offset + 3 * width)
        position = offset + (3 + blocks) * width
        chunks = []
        for k, compressed in enumerate(sizes):
            size = last_size if k == blocks - 1 and last_size else block_size
            chunks.append(lz4_block(raw[position:position + compressed], size))
            position += compressed
        blob = b"".join(chunks)
        code = types[attributes["type"]]
        values = struct.unpack("<%d%s" % (len(blob) // struct.calcsize(code), code), blob)
        components = int(attributes.get("NumberOfComponents", "1"))
        if components > 1:
            values = [values[i:i + components] for i in range(0, len(values), components)]
        name = "Points" if section == "Points" else attributes.get("Name")
        arrays.setdefault(name, values)
    return arrays


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
    contacts = read_vtk(files[-1])
    closed = [k for k, state in enumerate(contacts["state"]) if state != 0]
    if not closed:
        sys.exit("%s: no closed contact" % files[-1])
    x = [contacts["Points"][k][0] for k in closed]
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
