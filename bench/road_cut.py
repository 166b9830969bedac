#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""A road cut in jointed rock: about 105 blocks above a road, for the open-close budget.

    python3 bench/road_cut.py --out DIR [--model dda|vem|nmm] [--steps K] [--dt s]
                              [--open-close-max M]

writes DIR/road_cut.geo (gmsh, built-in kernel) and DIR/case.toml. Then

    nmm run DIR/case.toml --quiet    # K dynamic steps under gravity, from rest

The scene (units m): a hillside of rock 12 m high, its top 14 m wide, cut by a face of 65
degrees down to a road at y = 0 (the rock is the trapezoid (0, 0), (19.6, 0), (14, 12),
(0, 12)); it rests by contact (the joint "interface", phi 40) on a foundation 30 m wide and
3 m deep whose top right of the toe is the road, and the foundation's base is fixed. The
back face x = 0 is held on rollers (fixed in x). Two joint sets, fully persistent, cut the
rock into blocks: a bedding dipping 35 degrees out of the face (spacing 1.3 m) and cross
joints at 75 degrees into the slope (spacing 1.9 m), both with phi 30 degrees, so the
slabs that daylight in the face slide on the bedding (30 < 35) and the rest settle. Each
joint is one gmsh Line from boundary to boundary of the rock, carried on for a little into
the air where it leaves through the top, the back or the face, and ending exactly on the
interface (y = 0 is exact in floating point): every block is cut out, as DDA and VEM
regions need. The joints are placed without jitter at fixed offsets: with the defaults the
rock has 104 blocks (`nmm check` prints 105, the foundation included).

Case file: dynamic analysis, gravity, --steps K (default 100) fixed steps of --dt (default
1e-3 s), rock and foundation 2600 kg/m3, 10 GPa, nu 0.25; max_step_displacement 2% of the
bedding spacing over the model size, as bench/rock_mass.py; open_close_max not written
unless --open-close-max is given (nmm's default then applies).
"""

import argparse
import math
import os

from rock_mass import fmt  # the shortest text that reads back as the same double

HEIGHT, TOP, FACE = 12.0, 14.0, 65.0  # m, m, degrees
WIDTH, DEPTH = 30.0, 3.0  # the foundation, m
SETS = ((-35.0, 1.3, 0.37), (75.0, 1.9, 0.61))  # trace angle (deg), spacing (m), offset


def rock_polygon():
    toe = round(TOP + HEIGHT / math.tan(math.radians(FACE)), 3)
    return [(0.0, 0.0), (toe, 0.0), (TOP, HEIGHT), (0.0, HEIGHT)]


def clip(polygon, p, d):
    """The parameters (t0, t1) and edge indices of the part of the line p + t d inside the
    convex counter-clockwise @p polygon (Cyrus-Beck), or None."""
    t0, t1, e0, e1 = -math.inf, math.inf, None, None
    for i, a in enumerate(polygon):
        b = polygon[(i + 1) % len(polygon)]
        n = (b[1] - a[1], a[0] - b[0])  # outward normal of a counter-clockwise edge
        num = n[0] * (a[0] - p[0]) + n[1] * (a[1] - p[1])
        den = n[0] * d[0] + n[1] * d[1]
        if abs(den) < 1e-15:
            if num < 0.0:
                return None
            continue
        t = num / den
        if den < 0.0 and t > t0:
            t0, e0 = t, i
        elif den > 0.0 and t < t1:
            t1, e1 = t, i
    return (t0, e0, t1, e1) if t0 < t1 - 1e-9 else None


def joints(polygon):
    """Each set's joints as (set index, end points): boundary to boundary of the rock, on
    for 0.3 spacing into the air (less where that would reach the road), exactly on y = 0
    where a joint meets the interface (edge 0 of the polygon)."""
    xs = [x for x, _ in polygon]
    ys = [y for _, y in polygon]
    out = []
    for index, (angle, spacing, offset) in enumerate(SETS, start=1):
        a = math.radians(angle)
        d = (math.cos(a), math.sin(a))
        n = (-d[1], d[0])
        corners = [n[0] * x + n[1] * y for x in (min(xs), max(xs)) for y in (min(ys), max(ys))]
        k = math.floor(min(corners) / spacing - offset)
        while (k + offset) * spacing < max(corners):
            c = (k + offset) * spacing
            k += 1
            p = (c * n[0], c * n[1])
            part = clip(polygon, p, d)
            if part is None:
                continue
            t0, e0, t1, e1 = part
            ends = []
            for t, edge, outward in ((t0, e0, -1.0), (t1, e1, 1.0)):
                if edge == 0:
                    ends.append((p[0] + t * d[0], 0.0))
                    continue
                extra = 0.3 * spacing
                y = p[1] + t * d[1]
                if outward * d[1] < 0.0:  # going down: stay clear of the road
                    extra = min(extra, 0.5 * y / abs(d[1]))
                t += outward * extra
                ends.append((p[0] + t * d[0], p[1] + t * d[1]))
            out.append((index, ends))
    return out


def write_geo(path, polygon, lines):
    out = ["// A road cut in jointed rock, written by bench/road_cut.py (see its docstring).",
           "// Units: metres. Do not edit: regenerate instead."]
    emit = out.append
    toe = polygon[1][0]
    emit("Point(1) = {0, %s, 0};" % fmt(-DEPTH))
    emit("Point(2) = {%s, %s, 0};" % (fmt(WIDTH), fmt(-DEPTH)))
    emit("Point(3) = {%s, 0, 0};" % fmt(WIDTH))
    emit("Point(4) = {%s, 0, 0};   // the toe" % fmt(toe))
    emit("Point(5) = {0, 0, 0};")
    emit("Point(6) = {%s, %s, 0};   // the crest" % (fmt(TOP), fmt(HEIGHT)))
    emit("Point(7) = {0, %s, 0};" % fmt(HEIGHT))
    emit("Line(1) = {1, 2};   // base")
    emit("Line(2) = {2, 3};")
    emit("Line(3) = {3, 4};   // road")
    emit("Line(4) = {4, 5};   // interface, shared by both surfaces")
    emit("Line(5) = {5, 1};")
    emit("Line(6) = {4, 6};   // face")
    emit("Line(7) = {6, 7};   // top")
    emit("Line(8) = {7, 5};   // back")
    emit("Curve Loop(1) = {1, 2, 3, 4, 5};")
    emit("Plane Surface(1) = {1};   // foundation")
    emit("Curve Loop(2) = {-4, 6, 7, 8};")
    emit("Plane Surface(2) = {2};   // rock")
    point, line = 100, 100
    by_set = {}
    for index, ends in lines:
        ids = []
        for x, y in ends:
            point += 1
            emit("Point(%d) = {%s, %s, 0};" % (point, fmt(x), fmt(y)))
            ids.append(point)
        line += 1
        emit("Line(%d) = {%d, %d};" % (line, ids[0], ids[1]))
        by_set.setdefault(index, []).append(line)
    emit('Physical Surface("rock") = {2};')
    emit('Physical Surface("foundation") = {1};')
    emit('Physical Curve("interface") = {4};')
    emit('Physical Curve("base") = {1};')
    emit('Physical Curve("back") = {8};')
    for index, ids in sorted(by_set.items()):
        emit('Physical Curve("set%d") = {%s};' % (index, ", ".join(str(i) for i in ids)))
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def write_case(path, args):
    size = max(WIDTH, HEIGHT + DEPTH)
    g2 = 0.02 * min(s for _, s, _ in SETS) / size
    out = ["# A road cut in jointed rock (about 105 blocks), written by bench/road_cut.py;",
           "# every key is explained in docs/case-file.md.",
           'geometry = "road_cut.geo"',
           'title = "Road cut in jointed rock, %s blocks"' % args.model,
           "", "[cover_mesh]", 'kind = "regular"', "size = 1.0", "order = 0", ""]
    emit = out.append
    for name in ("rock", "foundation"):
        emit("[materials.%s]" % name)
        emit('model = "%s"' % args.model)
        emit("density = 2600.0\nyoung = 1.0e10\npoisson = 0.25\n")
    for index, (angle, spacing, _) in enumerate(SETS, start=1):
        emit("[joints.set%d]   # trace angle %g deg, spacing %g m" % (index, angle, spacing))
        emit("friction_angle = 30.0\n")
    emit("[joints.interface]\nfriction_angle = 40.0\n")
    emit("[contact]\nfriction_angle = 30.0\n")
    emit('[[boundary]]\ncurve = "base"\nfix = "xy"\n')
    emit('[[boundary]]\ncurve = "back"\nfix = "x"\n')
    emit("[[load]]\ngravity = [0.0, -9.81]\n")
    emit("[analysis]")
    emit('kind = "dynamic"')
    emit("steps = %d" % args.steps)
    emit("time_step = %s   # s, fixed" % fmt(args.dt))
    emit("max_step_displacement = %.6g   # 2 %% of the bedding spacing over the model size" % g2)
    if args.open_close_max:
        emit("open_close_max = %d" % args.open_close_max)
    emit("")
    emit('[output]\ndir = "out"\nevery = 100000000   # only step 0 and the last step are written')
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--out", required=True, help="folder for road_cut.geo and case.toml")
    p.add_argument("--model", choices=("dda", "vem", "nmm"), default="dda")
    p.add_argument("--steps", type=int, default=100, help="time steps (default 100)")
    p.add_argument("--dt", type=float, default=1e-3, help="time step in s (default 1e-3)")
    p.add_argument("--open-close-max", type=int, metavar="M",
                   help="[analysis] open_close_max (default: not written)")
    args = p.parse_args()
    os.makedirs(args.out, exist_ok=True)
    polygon = rock_polygon()
    lines = joints(polygon)
    write_geo(os.path.join(args.out, "road_cut.geo"), polygon, lines)
    write_case(os.path.join(args.out, "case.toml"), args)
    print("wrote %s/road_cut.geo (%d joints) and %s/case.toml" % (args.out, len(lines), args.out))


if __name__ == "__main__":
    main()
