#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The picture of examples/19_bolted_tunnel_stages (README.md) from a run's output, with the
Python standard library only (no ParaView, no matplotlib):

    python3 examples/19_bolted_tunnel_stages/picture.py examples/19_bolted_tunnel_stages/out \\
        docs/pictures/bolted_tunnel_stages.png

Draws the blocks around the tunnel in the last step file (the excavated ones are not in it),
displaced --magnify times their displacement (default 500), each filled by how far its
centroid moved since the excavation (blocks.csv, last output step): from white (nothing) to
red (the largest); the block outlines in black, the tunnel's outline before the excavation
in blue, and the bolts' bars (the boundary files' lines with a `bolt`), displaced as the blocks
from where they were installed, in green, thicker the larger their axial force.
"""
import glob
import math
import os
import re
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "scripts"))
from block_picture import (block_displacements, cells, fill, line,  # noqa: E402
                           picture_arguments, write_png)  # (scripts/block_picture.py)
from vtk_xml import read_arrays  # noqa: E402


def bolt_bars(path):
    """The bolts' bars of boundary file @p path as (axial force, p, q); none before the bolts
    are installed. The file's lines come after its (empty) vertices; the vertices' arrays are
    cut out so that read_arrays() finds the lines' connectivity first."""
    with open(path, "rb") as f:
        text = f.read().decode("latin-1")
    if 'Name="bolt"' not in text:
        return []
    text = re.sub(r"<Verts>.*?</Verts>", "", text, flags=re.S)
    with tempfile.NamedTemporaryFile("w", suffix=".vtp", encoding="latin-1",
                                     delete=False) as f:
        f.write(text)
    try:
        a = read_arrays(f.name, {"Points", "connectivity", "offsets", "bolt", "axial_force"})
    finally:
        os.unlink(f.name)
    points = a["Points"]
    bars = []
    start = 0
    for c, end in enumerate(a["offsets"]):
        ids = a["connectivity"][start:end]
        start = end
        if a["bolt"][c] >= 0:
            p, q = ((points[3 * i], points[3 * i + 1]) for i in ids[:2])
            bars.append((a["axial_force"][c], p, q))
    return bars


def main():
    parser = picture_arguments(__doc__, magnify=500.0, scale=40.0)
    parser.add_argument("--half", type=float, default=9.0,
                        help="half the width of the window around the tunnel, m")
    args = parser.parse_args()
    last = cells(sorted(glob.glob(os.path.join(args.out, "step_*.vtu")))[-1], args.magnify)
    displacement = block_displacements(args.out)
    largest = max(displacement.values())
    size = int(2 * args.half * args.scale)

    def pixel(p):
        return ((p[0] + args.half) * args.scale, (args.half - p[1]) * args.scale)

    image = [[(255, 255, 255)] * size for _ in range(size)]
    for block, polygon in last:
        f = min(1.0, displacement.get(block, 0.0) / largest)
        colour = (255, int(255 * (1.0 - 0.85 * f)), int(255 * (1.0 - f)))
        fill(image, size, size, [pixel(p) for p in polygon], colour)
    for _, polygon in last:
        for p, q in zip(polygon, polygon[1:] + polygon[:1]):
            line(image, size, size, pixel(p), pixel(q), (0, 0, 0))
    circle = [(3.0 * math.cos(t * math.pi / 90), 3.0 * math.sin(t * math.pi / 90))
              for t in range(181)]
    for p, q in zip(circle, circle[1:]):
        line(image, size, size, pixel(p), pixel(q), (60, 90, 200))
    # The bars where they were installed (the first boundary file with them) and now,
    # displaced as the blocks are.
    boundaries = sorted(glob.glob(os.path.join(args.out, "boundary_*.vtp")))
    bars = bolt_bars(boundaries[-1]) if boundaries else []
    installed = next((b for b in map(bolt_bars, boundaries) if len(b) == len(bars)), bars)

    def magnified(p0, p1):
        return tuple(a + args.magnify * (b - a) for a, b in zip(p0, p1))

    bars = [(force, magnified(p0, p), magnified(q0, q))
            for (force, p, q), (_, p0, q0) in zip(bars, installed)]
    strongest = max([abs(b[0]) for b in bars] or [1.0])
    for force, p, q in bars:
        width = 1 + int(4 * abs(force) / strongest)
        a, b = pixel(p), pixel(q)
        for k in range(-width // 2, width // 2 + 1):
            for j in range(-width // 2, width // 2 + 1):
                line(image, size, size, (a[0] + k, a[1] + j), (b[0] + k, b[1] + j), (0, 140, 60))
    os.makedirs(os.path.dirname(os.path.abspath(args.png)), exist_ok=True)
    write_png(args.png, image)
    print("%s: %d x %d pixels, the largest block displacement %.3f mm, %d bolt bars, the "
          "largest axial force %.1f kN" % (args.png, size, size, 1e3 * largest, len(bars),
                                           1e-3 * strongest))


if __name__ == "__main__":
    main()
