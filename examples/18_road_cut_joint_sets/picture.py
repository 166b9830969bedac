#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The picture of examples/18_road_cut_joint_sets (README.md) from a run's output, with the
Python standard library only (no ParaView, no matplotlib):

    python3 examples/18_road_cut_joint_sets/picture.py examples/18_road_cut_joint_sets/out \\
        docs/pictures/road_cut_joint_sets.png

Draws the last step file's blocks (cell array `block`), each filled by how far its centroid
moved (blocks.csv, last output step): grey below 1 mm, the others from yellow (the least of
them) to red (the largest); the block outlines in black; the outline at the start (step_000000.vtu) in
blue where the blocks have moved away from it. Displacements are drawn --magnify times their
size (default 20) so that the slide of a few centimetres shows.
"""
import argparse
import csv
import glob
import os
import struct
import sys
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "scripts"))
from vtk_xml import read_arrays  # noqa: E402  (scripts/vtk_xml.py: nmm's VTK files)


def cells(path, magnify):
    """Polygons of @p path as (block, [(x, y), ...]), displaced @p magnify times."""
    a = read_arrays(path, {"Points", "connectivity", "offsets", "block", "displacement"})
    points = a["Points"]
    u = a["displacement"]

    def at(i):
        return (points[3 * i] + (magnify - 1.0) * u[3 * i],
                points[3 * i + 1] + (magnify - 1.0) * u[3 * i + 1])

    result = []
    start = 0
    for c, end in enumerate(a["offsets"]):
        result.append((a["block"][c], [at(i) for i in a["connectivity"][start:end]]))
        start = end
    return result


def moved(out_dir):
    """Displacement of each block's centroid at the last output step of blocks.csv."""
    with open(os.path.join(out_dir, "blocks.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    last = max(int(r["step"]) for r in rows)
    return {int(r["block"]): (float(r["ux"]) ** 2 + float(r["uy"]) ** 2) ** 0.5
            for r in rows if int(r["step"]) == last}


def fill(image, width, height, polygon, colour):
    """Even-odd scanline fill of @p polygon (pixel coordinates)."""
    ys = [p[1] for p in polygon]
    for y in range(max(0, int(min(ys))), min(height, int(max(ys)) + 1)):
        yc = y + 0.5
        xs = []
        for (x0, y0), (x1, y1) in zip(polygon, polygon[1:] + polygon[:1]):
            if (y0 > yc) != (y1 > yc):
                xs.append(x0 + (yc - y0) * (x1 - x0) / (y1 - y0))
        xs.sort()
        for left, right in zip(xs[::2], xs[1::2]):
            for x in range(max(0, int(left + 0.5)), min(width, int(right + 0.5))):
                image[y][x] = colour


def line(image, width, height, p, q, colour):
    steps = int(max(abs(q[0] - p[0]), abs(q[1] - p[1]))) + 1
    for k in range(steps + 1):
        x = int(p[0] + (q[0] - p[0]) * k / steps)
        y = int(p[1] + (q[1] - p[1]) * k / steps)
        if 0 <= x < width and 0 <= y < height:
            image[y][x] = colour


def write_png(path, image):
    height, width = len(image), len(image[0])
    raw = b"".join(b"\0" + bytes(c for pixel in row for c in pixel) for row in image)

    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data +
                struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height,
                                                                   8, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("out", help="the run's output folder")
    parser.add_argument("png", help="the picture to write")
    parser.add_argument("--magnify", type=float, default=20.0)
    parser.add_argument("--scale", type=float, default=20.0, help="pixels per metre")
    args = parser.parse_args()
    steps = sorted(glob.glob(os.path.join(args.out, "step_*.vtu")))
    start, last = cells(steps[0], 1.0), cells(steps[-1], args.magnify)
    displacement = moved(args.out)
    largest = max(displacement.values())
    least = min([d for d in displacement.values() if d >= 1e-3] or [largest])
    xs = [p[0] for _, poly in start for p in poly]
    ys = [p[1] for _, poly in start for p in poly]
    margin = 1.0
    width = int((max(xs) - min(xs) + 2 * margin) * args.scale)
    height = int((max(ys) - min(ys) + 2 * margin) * args.scale)

    def pixel(p):
        return ((p[0] - min(xs) + margin) * args.scale,
                (max(ys) + margin - p[1]) * args.scale)

    image = [[(255, 255, 255)] * width for _ in range(height)]
    for block, polygon in last:
        d = displacement.get(block, 0.0)
        if d < 1e-3:
            colour = (200, 200, 200)
        else:
            f = (d - least) / (largest - least) if largest > least else 1.0
            colour = (230, int(220 * (1.0 - f)), 40)
        fill(image, width, height, [pixel(p) for p in polygon], colour)
    for _, polygon in start:
        for p, q in zip(polygon, polygon[1:] + polygon[:1]):
            line(image, width, height, pixel(p), pixel(q), (60, 90, 200))
    for _, polygon in last:
        for p, q in zip(polygon, polygon[1:] + polygon[:1]):
            line(image, width, height, pixel(p), pixel(q), (0, 0, 0))
    os.makedirs(os.path.dirname(os.path.abspath(args.png)), exist_ok=True)
    write_png(args.png, image)
    print("%s: %d x %d pixels, %d blocks moved more than 1 mm, the farthest %.2f mm" %
          (args.png, width, height, sum(d >= 1e-3 for d in displacement.values()),
           1e3 * largest))


if __name__ == "__main__":
    main()
