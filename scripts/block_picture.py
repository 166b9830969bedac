# SPDX-License-Identifier: MIT
"""Pictures of nmm's block output with the Python standard library only (no ParaView, no
matplotlib), for the examples' picture scripts (examples/18_road_cut_joint_sets/picture.py,
examples/19_bolted_tunnel_stages/picture.py): the polygons of a step file, filled and
outlined in an RGB pixel array, written as a PNG; the blocks' displacements from blocks.csv.
"""
import argparse
import csv
import math
import os
import struct
import zlib

from vtk_xml import read_arrays


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


def picture_arguments(doc, magnify, scale):
    """The command line of an example's picture script (its docstring @p doc): the run's
    output folder, the PNG, how many times the displacements are drawn, pixels per metre."""
    parser = argparse.ArgumentParser(description=doc.split("\n\n")[0])
    parser.add_argument("out", help="the run's output folder")
    parser.add_argument("png", help="the picture to write")
    parser.add_argument("--magnify", type=float, default=magnify)
    parser.add_argument("--scale", type=float, default=scale, help="pixels per metre")
    return parser


def block_displacements(out_dir):
    """How far each block's centroid has moved at the last output step of blocks.csv (since
    the start, or the last `reset_displacement`), the excavated blocks left out."""
    with open(os.path.join(out_dir, "blocks.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    last = max(int(r["step"]) for r in rows)
    return {int(r["block"]): math.hypot(float(r["ux"]), float(r["uy"]))
            for r in rows if int(r["step"]) == last and r["state"] != "excavated"}


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
