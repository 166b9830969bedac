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
import glob
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "scripts"))
from block_picture import (block_displacements, cells, fill, line,  # noqa: E402
                           picture_arguments, write_png)  # (scripts/block_picture.py)


def main():
    parser = picture_arguments(__doc__, magnify=20.0, scale=20.0)
    args = parser.parse_args()
    steps = sorted(glob.glob(os.path.join(args.out, "step_*.vtu")))
    start, last = cells(steps[0], 1.0), cells(steps[-1], args.magnify)
    displacement = block_displacements(args.out)
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
