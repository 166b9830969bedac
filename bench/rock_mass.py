#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""A jointed rock mass of about N blocks on a fixed foundation: the scene for timing a step.

    python3 bench/rock_mass.py --blocks N --model dda|vem|nmm --out DIR
                               [--seed S] [--steps K] [--cover-size h] [--sets 2|3]
                               [--set DIP:SPACING[:JITTER]]... [--aspect W/H] [--dt s]
                               [--open-close-max M] [--initial-equilibrium]

writes DIR/rock_mass.geo (gmsh, built-in kernel) and DIR/case.toml, and prints the planned
number of blocks. Then, for instance:

    nmm check DIR/case.toml          # covers, elements, blocks (rock blocks + 1 foundation)
    nmm mesh DIR/case.toml -o DIR/mesh
    nmm run DIR/case.toml --quiet    # K dynamic steps under gravity

The scene (units m):

- "rock": the rectangle [0, W] x [0, H], W = aspect H (default aspect 2), a Physical
  Surface with the material model of --model.
- "foundation": the rectangle [0, W] x [-D, 0] below it, the same model by default
  (--foundation-model nmm gives an NMM foundation under DDA or VEM blocks). Its bottom,
  the Physical Curve "base", is fixed in x and y.
- "interface": the line y = 0 between them, one gmsh curve shared by both surfaces and
  listed as a joint, so the rock blocks rest on the foundation by contact, not bonded.
- joint sets "set1", "set2" (and "set3"): fully persistent straight joints. Set i has the
  trace angle DIP_i (degrees, counter-clockwise from the +x axis: 0 is horizontal bedding,
  90 vertical; only the trace in the section matters) and the mean spacing SPACING_i (m,
  measured normal to the joints). Joint k of a set lies at the distance
  (offset + k + u_k JITTER) SPACING from the origin, where the offset is drawn once per
  set and u_k in [-1/2, 1/2] once per joint, both from --seed (string-seeded
  random.Random: the same seed gives the same joints on every machine and Python 3).
  Joints in one set stay parallel, and with JITTER < 1 no two are closer than
  (1 - JITTER) SPACING before the moves described below.

Each joint is one straight gmsh Line that runs right across the rock: where it leaves the
rock through the top or a side it goes on for half a spacing into the air (nmm ignores the
part outside the material; the foundation is exactly as wide as the rock, so everything
beside or above the rock is air); where it meets the interface it ends exactly on it
(y = 0 is exact in floating point, so the end point lies exactly on the interface and the
T junction is exact). Crossings of joints with each other are not written: the cover
mesher finds them in its exact arrangement (docs/cover-mesher.md, "crossing joints,
T-junctions"), so nothing is split in the .geo. No joint ends inside the rock, so every
block is cut out completely, as DDA and VEM regions need.

No small blocks. After choosing the joints the script moves a joint parallel to itself
(by at most 0.45 of the smallest spacing, deterministically) wherever it passes within
0.15 of the smallest spacing of a corner of the rock, comes within 0.3 spacing of a joint
of its own set, or crosses another joint that close to the rock's boundary: each of these
would leave a small corner piece, a thin strip or a small triangle against the boundary,
which make poorly conditioned covers and stiff, light blocks. It prints how many joints it
could not fix (none with the default two sets). With three sets, small triangles where
three joints pass nearly through one point are inherent to persistent joints (every joint
crosses dozens of others) and are left; the script prints how many there are within 0.05
spacing (2, 26 and 308 at N = 100, 1000, 10000 with the default sets, seed 1), and nmm warns
about the smallest ones ("block ... is too small for the cover mesh").

Number of blocks. n chords of a convex region, no three through one point, cut it into
1 + n + (crossings inside) pieces, so the script counts the blocks exactly from the joints
it draws and chooses H (with W = aspect H and the spacings fixed, so blocks keep their
size, about 1 m2 with the default sets, and the mass grows with N) to bring that count
nearest N; adding one joint adds about sqrt(N) blocks, so the count lands within a few %
of N, and moving joints changes it by a few blocks. nmm's block count is the rock's blocks
plus one (the foundation).

Case file (docs/case-file.md): dynamic analysis, gravity, --steps K (default 5) steps of a
fixed time step --dt (default 1e-4 s; nmm still cuts a step when its open-close iteration
does not converge), rock and foundation 2600 kg/m3, 10 GPa, nu 0.25; joints and interface
Coulomb (35 and 40 degrees, no cohesion), base fixed exactly. Output: [output] every = 1e8,
so only step 0 and the last step are written (nmm always writes those two); history.csv
still gets a row per step and summary.json is written at the start and the end.
max_step_displacement is set so that the step displacement limit is 2 % of the smallest
spacing (the default, 1 % of the model size, makes the contact detection distance grow
with the model: docs/benchmarks.md). --initial-equilibrium sets [analysis]
initial_equilibrium = true (the blocks start with their weight on the contacts instead of
dropping into unloaded springs during the first steps); with the snapshot build measured
below it worked at N = 100 but stopped at N = 1000 ("the step matrix is singular ... this
body can move freely", at a small triangular block on the top and, with other joints, at a
block on a side). --open-close-max M writes [analysis] open_close_max = M: without it nmm
uses the scene's budget (docs/formulation.md, "Open-close budget"), which ran the first 80
steps of N = 100, 1000 and 10000 (model dda) uncut on 2026-12-02, where a fixed 6 cut 11,
12 and 35 of them (docs/benchmarks.md, "Open-close budget"). For model nmm the cover size is
chosen so that the mean block area holds about 3 math triangles, which the joints cut into
a handful of elements (9 to 10 elements and covers per block at N = 100, 1000, 10000);
--cover-size overrides it. DDA and VEM regions do not use the cover size (it is still
written: [cover_mesh] size is required); an NMM foundation does.

Measured (2 cores, a snapshot build of nmm 0.1.0, default two sets, seed 1, model nmm;
"cover system" time printed by `nmm mesh`): N = 100: 101 rock blocks planned, nmm 102
blocks, 1021 elements, 0.04 s; N = 1000: 1003 planned, 1004 blocks, 9438 elements, 0.41 s;
N = 10000: 10004 planned, 10005 blocks, 94380 elements, 4.2 s. `nmm run` of N = 100 (5
steps): 0.69 s, 10 step cuts.
"""

import argparse
import bisect
import math
import os
import random
import sys

DEFAULT_SETS = {
    2: [(25.0, 1.0, 0.3), (110.0, 1.2, 0.3)],
    3: [(25.0, 1.4, 0.3), (110.0, 1.6, 0.3), (160.0, 2.4, 0.3)],
}
TRIANGLES_PER_BLOCK = 3.0  # math triangles per mean block area for model nmm
FLAW_DISTANCE = 0.15  # no tiny blocks: see flaws_of(); as a fraction of the smallest spacing


class JointSet:
    def __init__(self, index, dip, spacing, jitter, seed):
        self.index = index
        self.dip = dip
        self.spacing = spacing
        self.jitter = jitter
        self.seed = seed
        a = math.radians(dip)
        self.d = (math.cos(a), math.sin(a))  # along the joints
        self.n = (-math.sin(a), math.cos(a))  # normal to them
        self.offset = random.Random("rock_mass:%d:set%d:offset" % (seed, index)).random()
        self._cache = {}

    def distance(self, k):
        """n . p of joint k (m): the same for every domain size, so a larger rock only adds
        joints."""
        if k not in self._cache:
            u = random.Random("rock_mass:%d:set%d:joint%d" % (self.seed, self.index, k)).random()
            self._cache[k] = (self.offset + k + (u - 0.5) * self.jitter) * self.spacing
        return self._cache[k]

    def joints(self, w, h):
        """The distances c of this set's joints that cut the open rectangle [0,w] x [0,h]."""
        corners = [self.n[0] * x + self.n[1] * y for x in (0.0, w) for y in (0.0, h)]
        lo, hi = min(corners), max(corners)
        k0 = math.floor(lo / self.spacing - self.offset) - 2
        k1 = math.ceil(hi / self.spacing - self.offset) + 2
        return [c for c in (self.distance(k) for k in range(k0, k1 + 1)) if lo < c < hi]


def clip(js, c, w, h):
    """The part of the line n . p = c inside [0,w] x [0,h]: (t0, side0, t1, side1) along d
    from the foot point c n, with the side ("left", "right", "bottom", "top") each end
    leaves through; None if it misses."""
    p0 = (c * js.n[0], c * js.n[1])
    t0, t1 = -math.inf, math.inf
    s0 = s1 = None
    for axis, lo_side, hi_side, size in ((0, "left", "right", w), (1, "bottom", "top", h)):
        dv, pv = js.d[axis], p0[axis]
        if abs(dv) < 1e-15:
            if not (0.0 < pv < size):
                return None
            continue
        ta, tb = (0.0 - pv) / dv, (size - pv) / dv
        sa, sb = lo_side, hi_side
        if ta > tb:
            ta, tb, sa, sb = tb, ta, sb, sa
        if ta > t0:
            t0, s0 = ta, sa
        if tb < t1:
            t1, s1 = tb, sb
    if not t0 < t1:
        return None
    return t0, s0, t1, s1


def crossing(a, ca, b, cb):
    """The point where n_a . p = ca and n_b . p = cb, or None if parallel."""
    det = a.n[0] * b.n[1] - a.n[1] * b.n[0]
    if abs(det) < 1e-12:
        return None
    return ((ca * b.n[1] - cb * a.n[1]) / det, (a.n[0] * cb - b.n[0] * ca) / det)


def plan(sets, w, h):
    """Joints (set, c) cutting the rock and the number of blocks they make."""
    return count_blocks([(js, c) for js in sets for c in js.joints(w, h)], w, h)


def flaws_of(i, lines, w, h, delta):
    """How many flaws joint i makes with the others, each of which would leave a small block
    or a thin strip: passing within delta of a corner of the rock, within 2 delta of a joint
    of its own set, or crossing another joint within delta of the rock's boundary (a small
    triangle against it). Three joints of three sets through nearly one point (a small
    triangle inside) are not flaws: with persistent joints every joint crosses many others,
    so they cannot be avoided by moving joints; near_triples() counts them."""
    js, c = lines[i]
    n = 0
    for x, y in ((0.0, 0.0), (w, 0.0), (w, h), (0.0, h)):
        if abs(js.n[0] * x + js.n[1] * y - c) < delta:
            n += 1
    for j, (other, c2) in enumerate(lines):
        if j == i:
            continue
        if other is js:
            if abs(c2 - c) < 2.0 * delta:
                n += 1
            continue
        p = crossing(js, c, other, c2)
        if p is None or not (-delta < p[0] < w + delta and -delta < p[1] < h + delta):
            continue
        if min(abs(p[0]), abs(p[0] - w), abs(p[1]), abs(p[1] - h)) < delta:
            n += 1
    return n


def near_triples(lines, w, h, distance):
    """With three sets: how many crossings of a set-1 and a set-2 joint inside the rock lie
    within distance of a set-3 joint (each a small triangular block)."""
    third = sorted({js for js, _ in lines}, key=lambda js: js.index)
    if len(third) < 3:
        return 0
    third = third[2]
    members = sorted(c for js, c in lines if js is third)
    others = [(js, c) for js, c in lines if js is not third]
    n = 0
    for i in range(len(others)):
        a, ca = others[i]
        for j in range(i + 1, len(others)):
            b, cb = others[j]
            if a is b:
                continue
            p = crossing(a, ca, b, cb)
            if p is None or not (0.0 < p[0] < w and 0.0 < p[1] < h):
                continue
            v = third.n[0] * p[0] + third.n[1] * p[1]
            k = bisect.bisect_left(members, v)
            n += sum(1 for c3 in members[max(k - 1, 0):k + 1] if abs(c3 - v) < distance)
    return n


def remove_flaws(lines, w, h, delta):
    """Moves joints parallel to themselves (by at most 3 delta, deterministically) so that
    none has a flaw (flaws_of()); returns the new list and the number of joints still
    flawed (0 unless no shift helped)."""
    lines = list(lines)
    shifts = [0.25 * m * delta * sign for m in range(1, 13) for sign in (1.0, -1.0)]
    for _ in range(10):
        changed = False
        for i in range(len(lines)):
            if flaws_of(i, lines, w, h, delta) == 0:
                continue
            js, base = lines[i]
            best = None
            for shift in shifts:
                lines[i] = (js, base + shift)
                n = flaws_of(i, lines, w, h, delta)
                if best is None or n < best[0]:
                    best = (n, shift)
                if n == 0:
                    break
            lines[i] = (js, base + best[1])
            changed = True
        if not changed:
            break
    return lines, sum(1 for i in range(len(lines)) if flaws_of(i, lines, w, h, delta))


def count_blocks(lines, w, h):
    """1 + joints + crossings inside the rock (lines that no longer cut it are dropped)."""
    lines = [(js, c) for js, c in lines if clip(js, c, w, h) is not None]
    inside = 0
    for i in range(len(lines)):
        for j in range(i + 1, len(lines)):
            a, ca = lines[i]
            b, cb = lines[j]
            if a is b:
                continue
            p = crossing(a, ca, b, cb)
            if p is not None and 0.0 < p[0] < w and 0.0 < p[1] < h:
                inside += 1
    return lines, 1 + len(lines) + inside, inside


def choose_height(sets, target, aspect):
    """The height H (rounded to mm) whose block count is nearest the target."""
    count = lambda h: plan(sets, aspect * h, h)[1]
    hi = max(js.spacing for js in sets)
    while count(hi) < target:
        hi *= 2.0
    lo = 0.0
    for _ in range(60):  # smallest H with count >= target (the count grows with H)
        mid = 0.5 * (lo + hi)
        if count(mid) >= target:
            hi = mid
        else:
            lo = mid
    best = None
    for h in {round(lo, 3), round(hi, 3), math.floor(lo * 1000) / 1000, math.ceil(hi * 1000) / 1000}:
        if h <= 0.0:
            continue
        n = count(h)
        if best is None or abs(n - target) < abs(best[1] - target):
            best = (h, n)
    return best[0]


def fmt(x):
    """The shortest text that reads back as the same double."""
    if x == 0.0:
        return "0"
    return repr(float(x))


def write_geo(path, sets, lines, w, h, depth, planned, args):
    out = []
    emit = out.append
    emit("// Jointed rock mass of %d blocks on a fixed foundation, written by bench/rock_mass.py" % planned)
    emit("// (--blocks %d --seed %d). Units: metres. Rock [0, %s] x [0, %s], foundation below it"
         % (args.blocks, args.seed, fmt(w), fmt(h)))
    emit("// down to y = -%s. Joints are single straight lines from boundary to boundary; the"
         % fmt(depth))
    emit("// cover mesher computes their crossings exactly. Do not edit: regenerate instead.")
    for js in sets:
        emit("//   set%d: trace angle %g deg, spacing %g m, jitter %g" % (js.index, js.dip, js.spacing, js.jitter))
    emit("")
    emit("Point(1) = {0, %s, 0};" % fmt(-depth))
    emit("Point(2) = {%s, %s, 0};" % (fmt(w), fmt(-depth)))
    emit("Point(3) = {%s, 0, 0};" % fmt(w))
    emit("Point(4) = {0, 0, 0};")
    emit("Point(5) = {%s, %s, 0};" % (fmt(w), fmt(h)))
    emit("Point(6) = {0, %s, 0};" % fmt(h))
    emit("Line(1) = {1, 2};   // base")
    emit("Line(2) = {2, 3};")
    emit("Line(3) = {3, 4};   // interface, shared by both surfaces")
    emit("Line(4) = {4, 1};")
    emit("Line(5) = {3, 5};")
    emit("Line(6) = {5, 6};")
    emit("Line(7) = {6, 4};")
    emit("Curve Loop(1) = {1, 2, 3, 4};")
    emit("Plane Surface(1) = {1};   // foundation")
    emit("Curve Loop(2) = {-3, 5, 6, 7};")
    emit("Plane Surface(2) = {2};   // rock")
    emit("")
    by_set = {js.index: [] for js in sets}
    point, line = 100, 100
    for js, c in lines:
        t0, s0, t1, s1 = clip(js, c, w, h)
        margin = 0.5 * js.spacing
        ends = []
        for t, side, outward in ((t0, s0, -1.0), (t1, s1, 1.0)):
            if side == "bottom":
                # exactly on the interface: y = 0 is exact, so the T junction is exact
                x = c * js.n[0] + t * js.d[0]
                ends.append((x, 0.0))
            else:
                t += outward * margin  # into the air beside or above the rock
                ends.append((c * js.n[0] + t * js.d[0], c * js.n[1] + t * js.d[1]))
        p = []
        for x, y in ends:
            point += 1
            emit("Point(%d) = {%s, %s, 0};" % (point, fmt(x), fmt(y)))
            p.append(point)
        line += 1
        emit("Line(%d) = {%d, %d};" % (line, p[0], p[1]))
        by_set[js.index].append(line)
    emit("")
    emit('Physical Surface("rock") = {2};')
    emit('Physical Surface("foundation") = {1};')
    emit('Physical Curve("interface") = {3};')
    emit('Physical Curve("base") = {1};')
    for js in sets:
        ids = by_set[js.index]
        emit('Physical Curve("set%d") = {%s};' % (js.index, ", ".join(str(i) for i in ids)))
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def write_case(path, sets, w, h, depth, planned, cover, args):
    foundation_model = args.model if args.foundation_model == "same" else args.foundation_model
    smallest = min(js.spacing for js in sets)
    model_size = max(w, h + depth)
    g2 = 0.02 * smallest / model_size
    lines = []
    emit = lines.append
    emit("# Jointed rock mass of %d blocks on a fixed foundation, for timing a step; written by" % planned)
    emit("# bench/rock_mass.py --blocks %d --model %s --seed %d --steps %d (see its docstring)."
         % (args.blocks, args.model, args.seed, args.steps))
    emit("# Every key is explained in docs/case-file.md.")
    emit('geometry = "rock_mass.geo"')
    emit('title = "Jointed rock mass, %d %s blocks"' % (planned, args.model))
    emit("")
    emit("[cover_mesh]")
    emit('kind = "regular"')
    emit("size = %s   # m: about %g math triangles per mean block (used by nmm regions only)"
         % (fmt(cover), TRIANGLES_PER_BLOCK))
    emit("order = 0")
    emit("")
    for name, model in (("rock", args.model), ("foundation", foundation_model)):
        emit("[materials.%s]" % name)
        emit('model = "%s"' % model)
        emit("density = 2600.0")
        emit("young = 1.0e10")
        emit("poisson = 0.25")
        emit("")
    for js in sets:
        emit("[joints.set%d]   # trace angle %g deg, spacing %g m" % (js.index, js.dip, js.spacing))
        emit("friction_angle = 35.0")
        emit("")
    emit("[joints.interface]   # the rock rests on the foundation by contact")
    emit("friction_angle = 40.0")
    emit("")
    emit("[contact]")
    emit("friction_angle = 35.0")
    emit("")
    emit("[[boundary]]")
    emit('curve = "base"')
    emit('fix = "xy"')
    emit("")
    emit("[[load]]")
    emit("gravity = [0.0, -9.81]")
    emit("")
    emit("[analysis]")
    emit('kind = "dynamic"')
    emit("steps = %d" % args.steps)
    emit("time_step = %s   # s, fixed" % fmt(args.dt))
    emit("max_step_displacement = %.6g   # 2 %% of the smallest spacing (%g m) over the model size %s m"
         % (g2, smallest, fmt(model_size)))
    if args.open_close_max:
        emit("open_close_max = %d" % args.open_close_max)
    if args.initial_equilibrium:
        emit("initial_equilibrium = true")
    if args.solver != "cholmod":
        emit('solver = "%s"' % args.solver)
    emit("")
    emit("[output]")
    emit('dir = "out"')
    emit("every = 100000000   # only step 0 and the last step are written")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def parse_set(text):
    parts = text.split(":")
    if len(parts) not in (2, 3):
        raise argparse.ArgumentTypeError("a joint set is DIP:SPACING[:JITTER], not %r" % text)
    try:
        dip, spacing = float(parts[0]), float(parts[1])
        jitter = float(parts[2]) if len(parts) == 3 else 0.0
    except ValueError:
        raise argparse.ArgumentTypeError("a joint set is DIP:SPACING[:JITTER] (numbers), not %r" % text)
    if not spacing > 0.0 or not 0.0 <= jitter < 1.0:
        raise argparse.ArgumentTypeError("%r: SPACING must be > 0 and 0 <= JITTER < 1" % text)
    return dip, spacing, jitter


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--blocks", type=int, required=True, help="about how many rock blocks")
    p.add_argument("--model", choices=("dda", "vem", "nmm"), required=True)
    p.add_argument("--out", required=True, help="folder for rock_mass.geo and case.toml")
    p.add_argument("--seed", type=int, default=1, help="joint offsets and jitter (default 1)")
    p.add_argument("--steps", type=int, default=5, help="time steps (default 5)")
    p.add_argument("--cover-size", type=float, help="math triangle size (m); default: about "
                   "%g triangles per mean block" % TRIANGLES_PER_BLOCK)
    p.add_argument("--sets", type=int, choices=(2, 3), default=2,
                   help="number of default joint sets (default 2), as angle/spacing: "
                   + "; ".join("%d: %s" % (k, ", ".join("%g deg/%g m" % (d, sp) for d, sp, _ in v))
                               for k, v in sorted(DEFAULT_SETS.items()))
                   + " (jitter 0.3)")
    p.add_argument("--set", action="append", type=parse_set, metavar="DIP:SPACING[:JITTER]",
                   help="a joint set instead of the defaults (give it 2 or 3 times)")
    p.add_argument("--aspect", type=float, default=2.0, help="rock width / height (default 2)")
    p.add_argument("--dt", type=float, default=1e-4, help="time step in s (default 1e-4)")
    p.add_argument("--foundation-model", choices=("same", "dda", "vem", "nmm"), default="same",
                   help="model of the foundation (default: the same as --model)")
    p.add_argument("--open-close-max", type=int, metavar="M",
                   help="[analysis] open_close_max (1 to 100; default: not written, the scene's budget)")
    p.add_argument("--solver", choices=("cholmod", "pcg"), default="cholmod",
                   help="[analysis] solver (default cholmod, not written)")
    p.add_argument("--initial-equilibrium", action="store_true",
                   help="start from the static equilibrium under gravity")
    args = p.parse_args(argv)
    if args.blocks < 4:
        p.error("--blocks must be at least 4")
    if args.steps < 1:
        p.error("--steps must be at least 1")
    if not args.dt > 0.0 or not args.aspect > 0.0:
        p.error("--dt and --aspect must be > 0")
    if args.open_close_max is not None and not 1 <= args.open_close_max <= 100:
        p.error("--open-close-max must be 1 to 100")
    if args.cover_size is not None and not args.cover_size > 0.0:
        p.error("--cover-size must be > 0")
    specs = args.set if args.set else DEFAULT_SETS[args.sets]
    if len(specs) not in (2, 3):
        p.error("give 2 or 3 joint sets (--set), not %d" % len(specs))
    dips = [s[0] % 180.0 for s in specs]
    if len(set(round(d, 9) for d in dips)) != len(dips):
        p.error("two joint sets are parallel")

    sets = [JointSet(i + 1, dip, spacing, jitter, args.seed) for i, (dip, spacing, jitter) in enumerate(specs)]
    h = choose_height(sets, args.blocks, args.aspect)
    w = round(args.aspect * h, 3)
    lines, _, _ = plan(sets, w, h)
    delta = FLAW_DISTANCE * min(js.spacing for js in sets)
    lines, left = remove_flaws(lines, w, h, delta)
    lines, planned, inside = count_blocks(lines, w, h)
    depth = round(max(2.0 * max(js.spacing for js in sets), 0.1 * h), 3)
    mean_block = w * h / planned
    cover = args.cover_size or float("%.3g" % math.sqrt(4.0 * mean_block / (math.sqrt(3.0) * TRIANGLES_PER_BLOCK)))

    os.makedirs(args.out, exist_ok=True)
    write_geo(os.path.join(args.out, "rock_mass.geo"), sets, lines, w, h, depth, planned, args)
    write_case(os.path.join(args.out, "case.toml"), sets, w, h, depth, planned, cover, args)

    per_set = ", ".join("set%d %d" % (js.index, sum(1 for s, _ in lines if s is js)) for js in sets)
    triangles = (w * (h + depth)) / (math.sqrt(3.0) / 4.0 * cover * cover)
    off = 100.0 * (planned - args.blocks) / args.blocks
    print("rock_mass: planned %d rock blocks (%+.1f%% of %d), %d with the foundation"
          % (planned, off, args.blocks, planned + 1))
    print("  rock %s x %s m on a foundation %s m deep; mean block %.3g m2"
          % (fmt(w), fmt(h), fmt(depth), mean_block))
    print("  joints: %d (%s), %d crossings inside the rock" % (len(lines), per_set, inside))
    if left:
        print("  warning: %d joints still pass within %g m of a corner or a joint of their set, or "
              "cross another within %g m of the boundary (small blocks there)" % (left, 2 * delta, delta))
    if len(sets) == 3:
        small = 0.05 * min(js.spacing for js in sets)
        print("  three sets: %d places where three joints pass within %g m of one point (small "
              "triangular blocks)" % (near_triples(lines, w, h, small), small))
    print("  model %s, cover size %s m (about %.0f math triangles), %d steps of %s s"
          % (args.model, fmt(cover), triangles, args.steps, fmt(args.dt)))
    print("  wrote %s and %s" % (os.path.join(args.out, "rock_mass.geo"), os.path.join(args.out, "case.toml")))
    return 0


if __name__ == "__main__":
    sys.exit(main())
