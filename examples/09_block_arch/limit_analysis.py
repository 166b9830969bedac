#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Collapse load of a voussoir arch under a point load on its key block (examples/09).

Heyman's masonry theory: no tension, infinite compressive strength, no sliding. The arch
then fails by a mechanism of rigid blocks turning about hinges at the ends of its joints,
and the collapse load is the smallest load at which the load and the weights do positive
virtual work in a kinematically admissible mechanism (upper-bound theorem). A thrust line
that carries that load inside the arch (lower-bound theorem) proves it exact.

The arch: n voussoirs with straight faces (trapezoids) between radial joints at the angles
pi k / n, k = 0 .. n, from the right springing (k = 0, on the x axis) to the left one
(k = n); joint k runs from the intrados point ri (cos, sin) to the extrados point
re (cos, sin). The springing joints 0 and n sit on a fixed base. The load P acts
downwards at the middle of the key block's extrados face (the crown).

Mechanisms (upper bound). A fixed arch needs four hinges, at joints i < j < k < l: the
blocks i..j-1 (body A) turn about hinge 1, the blocks k..l-1 (body C) about hinge 4, the
blocks j..k-1 (body B) are the coupler; the rest of the arch stays put. A hinge sits at the
intrados or the extrados end of its joint. A hinge at the intrados opens the joint at the
extrados: the body on its left (larger angle) turns counter-clockwise relative to the body
on its right; a hinge at the extrados the other way round. Every one of the 16
intrados/extrados choices of every four joints is tried (non-alternating ones are
admissible too, they never govern here); those whose relative rotations have the opening
signs are admissible. With the rate of A's rotation set to 1:

    L = downward velocity of the crown (the load's work rate per unit load)
    G = sum over moving blocks of W_b x downward velocity of its centroid

and the arch collapses in that mechanism when P L + G > 0: P_c = min over L > 0 of -G / L.

Thrust line (lower bound), for the symmetric arch: the key block pushes each half with
(H, -(P + W_key) / 2) through one end of its joint; H and P follow from the thrust line
passing through the right half's other two critical hinges; then the line must lie inside
every joint (between intrados and extrados) and the arch is safe up to that P. Where it
crosses each joint the script also gives the friction angle that joint needs not to slide
(Heyman's theory assumes it does not).

Collapse motion, for comparison with nmm's run: the symmetric combination of the critical
mechanisms moved with finite rotations (symmetric_fall(): rigid blocks, hinges fixed at
the predicted joints) gives the crown's fall in time under the case's load history.

Plain Python 3 (no numpy). Run with no arguments for the arch of examples/09; --help for
the options; --check for the self-checks (about 10 s): mirror pairs, the lower bound, the
collapse motion against virtual work, Milankovitch's minimum thickness of a semicircular
arch under its own weight, the sign of P_c on either side of it.
"""

import argparse
import itertools
import math
import sys

INTRADOS, EXTRADOS = 0, 1
SIDE = ("intrados", "extrados")


class Arch:
    """Geometry and weights of a semicircular voussoir arch of n blocks (per metre)."""

    def __init__(self, blocks, inner, outer, density=2500.0, gravity=9.81, sectors=False):
        """sectors: true annular-sector voussoirs instead of trapezoids (for the checks)."""
        self.n = blocks
        self.inner = inner
        self.outer = outer
        self.density = density
        self.angle = [math.pi * k / blocks for k in range(blocks + 1)]
        # hinge[k][side]: the intrados and extrados ends of joint k
        self.hinge = [[(r * math.cos(a), r * math.sin(a)) for r in (inner, outer)]
                      for a in self.angle]
        self.area, self.centroid, self.polar = [], [], []
        for b in range(blocks):
            if sectors:
                props = annular_sector(inner, outer, self.angle[b], self.angle[b + 1])
            else:
                props = polygon_properties([self.hinge[b][0], self.hinge[b][1],
                                            self.hinge[b + 1][1], self.hinge[b + 1][0]])
            self.area.append(props[0])
            self.centroid.append(props[1])
            self.polar.append(props[2])  # polar second moment of area about the centroid
        self.weight = [density * gravity * a for a in self.area]
        self.key = blocks // 2
        top = self.hinge[self.key][1], self.hinge[self.key + 1][1]
        self.crown = (0.5 * (top[0][0] + top[1][0]), 0.5 * (top[0][1] + top[1][1]))
        if sectors:
            self.crown = (0.0, outer)
        # Prefix sums over blocks of W and W x_c: a group's weight work needs only these.
        self.sum_w, self.sum_wx = [0.0], [0.0]
        for b in range(blocks):
            self.sum_w.append(self.sum_w[-1] + self.weight[b])
            self.sum_wx.append(self.sum_wx[-1] + self.weight[b] * self.centroid[b][0])

    def total_weight(self):
        return self.sum_w[-1]

    def thickness(self):
        return self.outer - self.inner


def polygon_properties(points):
    """Area, centroid and polar second moment about the centroid of a simple polygon."""
    a = cx = cy = ixx = iyy = 0.0
    for (x0, y0), (x1, y1) in zip(points, points[1:] + points[:1]):
        cross = x0 * y1 - x1 * y0
        a += cross
        cx += (x0 + x1) * cross
        cy += (y0 + y1) * cross
        ixx += (y0 * y0 + y0 * y1 + y1 * y1) * cross
        iyy += (x0 * x0 + x0 * x1 + x1 * x1) * cross
    a *= 0.5
    cx /= 6.0 * a
    cy /= 6.0 * a
    return a, (cx, cy), (ixx + iyy) / 12.0 - a * (cx * cx + cy * cy)


def annular_sector(inner, outer, a0, a1):
    """Area, centroid and polar second moment about the centroid of an annular sector."""
    half, mid = 0.5 * (a1 - a0), 0.5 * (a0 + a1)
    area = half * (outer ** 2 - inner ** 2)
    r = 2.0 * (outer ** 3 - inner ** 3) * math.sin(half) / (3.0 * (outer ** 2 - inner ** 2) * half)
    polar = 0.5 * half * (outer ** 4 - inner ** 4) - area * r * r
    return area, (r * math.cos(mid), r * math.sin(mid)), polar


class Mechanism:
    """Four hinges (joint, side), body rotation rates (A, B, C), work rates L and G."""

    def __init__(self, joints, sides, rates, load_work, weight_work):
        self.joints, self.sides, self.rates = joints, sides, rates
        self.load_work, self.weight_work = load_work, weight_work

    def collapse_load(self):
        return -self.weight_work / self.load_work

    def hinges(self):
        return list(zip(self.joints, self.sides))

    def describe(self):
        return ", ".join(f"{j} {SIDE[s]}" for j, s in self.hinges())


def mechanisms(arch):
    """Every kinematically admissible four-hinge mechanism of @p arch."""
    hinge, key, crown = arch.hinge, arch.key, arch.crown
    sum_w, sum_wx = arch.sum_w, arch.sum_wx
    sides_list = list(itertools.product((INTRADOS, EXTRADOS), repeat=4))
    for joints in itertools.combinations(range(arch.n + 1), 4):
        i, j, k, l = joints
        for sides in sides_list:
            (x1, y1), (x2, y2) = hinge[i][sides[0]], hinge[j][sides[1]]
            (x3, y3), (x4, y4) = hinge[k][sides[2]], hinge[l][sides[3]]
            # B's velocity at hinge 2 (A about hinge 1, rate 1) plus B's turn from hinge 2
            # to hinge 3 is C's velocity at hinge 3 (about hinge 4):
            # (h2 - h1) + wb (h3 - h2) - wc (h3 - h4) = 0.
            ax, ay = x3 - x2, y3 - y2
            bx, by = x4 - x3, y4 - y3
            det = ax * by - ay * bx
            if abs(det) <= 1e-12 * math.hypot(ax, ay) * math.hypot(bx, by):
                continue  # hinges 1, 2 and 3, 4 in line: no one-degree mechanism
            rx, ry = x1 - x2, y1 - y2
            wb = (rx * by - ry * bx) / det
            wc = (ax * ry - ay * rx) / det
            # Relative rotation (left body minus right body) at each hinge: positive at an
            # intrados hinge, negative at an extrados one. The mechanism's sign is free:
            # take the one that opens hinge 1, then test the other three.
            sign = 1.0 if (sides[0] == INTRADOS) else -1.0
            relative = (sign, sign * (wb - 1.0), sign * (wc - wb), -sign * wc)
            if not all(abs(r) > 1e-12 and (r > 0) == (s == INTRADOS)
                       for r, s in zip(relative[1:], sides[1:])):
                continue
            wa, wb, wc = sign, sign * wb, sign * wc
            # Downward velocity of a point (x, y) turning at rate w about (cx, cy):
            # -w (x - cx). B's points: hinge 2's velocity plus B's turn about hinge 2.
            v2 = -wa * (x2 - x1)
            weight_work = (
                -wa * (sum_wx[j] - sum_wx[i] - x1 * (sum_w[j] - sum_w[i]))
                + v2 * (sum_w[k] - sum_w[j])
                - wb * (sum_wx[k] - sum_wx[j] - x2 * (sum_w[k] - sum_w[j]))
                - wc * (sum_wx[l] - sum_wx[k] - x4 * (sum_w[l] - sum_w[k])))
            if i <= key < j:
                load_work = -wa * (crown[0] - x1)
            elif j <= key < k:
                load_work = v2 - wb * (crown[0] - x2)
            elif k <= key < l:
                load_work = -wc * (crown[0] - x4)
            else:
                load_work = 0.0
            yield Mechanism(joints, sides, (wa, wb, wc), load_work, weight_work)


def collapse(arch):
    """P_c, the mechanisms that give it, and whether the arch carries its own weight.

    Mechanisms within 1e-9 of P_c all count as critical (a symmetric arch gives mirror
    pairs). The arch cannot carry its own weight when some mechanism lets the weights do
    positive work (G > 0): then P_c < 0, or a mechanism the load does not drive collapses.
    """
    scale = arch.total_weight() * arch.thickness()
    best, critical, stands = math.inf, [], True
    for m in mechanisms(arch):
        if m.load_work > 1e-12 * arch.thickness():
            p = m.collapse_load()
            if p < best - 1e-9 * scale:
                best, critical = p, [m]
            elif abs(p - best) <= 1e-9 * scale:
                critical.append(m)
        if m.weight_work > 0.0:
            stands = False
    return best, critical, stands


def self_weight_work(arch):
    """The largest work rate of the weights alone over all mechanisms, per W x thickness.

    Positive: some mechanism lets the weights fall, the arch cannot carry its own weight.
    """
    scale = arch.total_weight() * arch.thickness()
    return max(m.weight_work for m in mechanisms(arch)) / scale


def minimum_thickness(blocks, low=0.100, high=0.112, iterations=12):
    """t/R at which a semicircular arch of annular sectors (centreline radius R = 1) of
    @p blocks voussoirs just carries its own weight (bisection on self_weight_work)."""
    for _ in range(iterations):
        t = 0.5 * (low + high)
        if self_weight_work(Arch(blocks, 1.0 - 0.5 * t, 1.0 + 0.5 * t, sectors=True)) > 0.0:
            low = t
        else:
            high = t
    return 0.5 * (low + high)


def block_velocities(arch, fields):
    """Velocity (vx, vy) of each block's centroid and its turning rate, in a motion.

    @p fields: (mechanism, amplitude) pairs whose velocity fields add up to the motion (one
    mechanism, or a mirror pair for the symmetric motion). Returns the list of (vx, vy, w)
    of the blocks and the motion's work rates (L, G).
    """
    velocity = [[0.0, 0.0, 0.0] for _ in range(arch.n)]
    load_work = weight_work = 0.0
    for m, amplitude in fields:
        i, j, k, l = m.joints
        h = [arch.hinge[q][s] for q, s in m.hinges()]
        wa, wb, wc = (amplitude * w for w in m.rates)
        v2 = (-wa * (h[1][1] - h[0][1]), wa * (h[1][0] - h[0][0]))
        for b in range(arch.n):
            cx, cy = arch.centroid[b]
            if i <= b < j:
                v = (-wa * (cy - h[0][1]), wa * (cx - h[0][0]), wa)
            elif j <= b < k:
                v = (v2[0] - wb * (cy - h[1][1]), v2[1] + wb * (cx - h[1][0]), wb)
            elif k <= b < l:
                v = (-wc * (cy - h[3][1]), wc * (cx - h[3][0]), wc)
            else:
                continue
            for c in range(3):
                velocity[b][c] += v[c]
        load_work += amplitude * m.load_work
        weight_work += amplitude * m.weight_work
    return velocity, load_work, weight_work


def crown_acceleration(arch, fields, load):
    """Downward acceleration of the crown, from rest, under @p load in a motion (fields as
    in block_velocities()). Lagrange with one coordinate q: q'' = (P L + G) / M, with
    M = sum m_b |v_b|^2 + J_b w_b^2 for q' = 1 (the velocity terms vanish at rest); the
    crown's acceleration is q'' L.
    """
    velocity, load_work, weight_work = block_velocities(arch, fields)
    mass = sum(arch.density * (arch.area[b] * (vx * vx + vy * vy) + arch.polar[b] * w * w)
               for b, (vx, vy, w) in enumerate(velocity))
    return (load * load_work + weight_work) / mass * load_work


def symmetric_fall(arch, spring, haunch, crown_side, load, end, dt=2e-4):
    """Fall of the crown in the symmetric collapse of rigid blocks, with finite rotations.

    spring, haunch: (joint, side) of the right half's lower hinges; the key block's right
    joint turns about its @p crown_side end. Body A (the blocks from the springing hinge to
    the haunch hinge) turns about the springing hinge, body B (from the haunch hinge to the
    key block) joins the haunch hinge to the key block, which drops without turning
    (symmetry): a slider-crank with one coordinate q, A's clockwise rotation. Lagrange:
    m(q) q'' + m'(q) q'^2 / 2 + V'(q) = 0, V the potential of the weights and the load, m
    from the blocks' velocities (by central differences). From rest; the arch moves once the
    load drives the mechanism. load(t): crown load, N/m. Returns (t, fall) pairs up to
    @p end, or until B stands upright and the linkage locks.
    """
    key = arch.key
    h0 = arch.hinge[spring[0]][spring[1]]
    h1 = arch.hinge[haunch[0]][haunch[1]]
    h2 = arch.hinge[key][crown_side]
    length = math.dist(h1, h2)
    direction = math.atan2(h2[1] - h1[1], h2[0] - h1[0])

    def turned(point, centre, angle, new_centre):
        c, s = math.cos(angle), math.sin(angle)
        dx, dy = point[0] - centre[0], point[1] - centre[1]
        return new_centre[0] + c * dx - s * dy, new_centre[1] + s * dx + c * dy

    def state(q):
        """Centroids and rotations of the right half's moving blocks, and the crown's fall."""
        p1 = turned(h1, h0, -q, h0)
        dx = h2[0] - p1[0]
        y2 = p1[1] + math.sqrt(length * length - dx * dx)
        beta = math.atan2(y2 - p1[1], dx) - direction
        blocks = []
        for b in range(spring[0], key):
            if b < haunch[0]:
                blocks.append((turned(arch.centroid[b], h0, -q, h0), -q))
            else:
                blocks.append((turned(arch.centroid[b], h1, beta, p1), beta))
        return blocks, h2[1] - y2

    def mass(q, h=1e-7):
        (plus, fall_plus), (minus, fall_minus) = state(q + h), state(q - h)
        m = arch.density * arch.area[key] * ((fall_plus - fall_minus) / (2 * h)) ** 2
        for b, ((cp, wp), (cm, wm)) in enumerate(zip(plus, minus), start=spring[0]):
            vx, vy, w = ((cp[0] - cm[0]) / (2 * h), (cp[1] - cm[1]) / (2 * h),
                         (wp - wm) / (2 * h))
            m += 2.0 * arch.density * (arch.area[b] * (vx * vx + vy * vy) + arch.polar[b] * w * w)
        return m

    def potential(q, p):
        blocks, fall = state(q)
        return (sum(2.0 * arch.weight[b] * c[1] for b, (c, _) in enumerate(blocks, start=spring[0]))
                - (arch.weight[key] + p) * fall)

    def acceleration(q, v, t, h=1e-6):
        force = -(potential(q + h, load(t)) - potential(q - h, load(t))) / (2 * h)
        if q <= 0.0 and v <= 0.0 and force <= 0.0:
            return 0.0  # at rest: the arch carries the load
        dm = (mass(q + h) - mass(q - h)) / (2 * h)
        return (force - 0.5 * dm * v * v) / mass(q)

    q = v = t = 0.0
    rows = []
    while t < end - 0.5 * dt:
        try:  # classical Runge-Kutta
            k1 = (v, acceleration(q, v, t))
            k2 = (v + 0.5 * dt * k1[1], acceleration(q + 0.5 * dt * k1[0], v + 0.5 * dt * k1[1],
                                                     t + 0.5 * dt))
            k3 = (v + 0.5 * dt * k2[1], acceleration(q + 0.5 * dt * k2[0], v + 0.5 * dt * k2[1],
                                                     t + 0.5 * dt))
            k4 = (v + dt * k3[1], acceleration(q + dt * k3[0], v + dt * k3[1], t + dt))
        except ValueError:
            break  # B upright: the linkage locks, the arch has fallen in
        q += dt * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0]) / 6
        v += dt * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1]) / 6
        q, v, t = max(q, 0.0), (v if q > 0.0 else 0.0), t + dt
        rows.append((t, state(q)[1]))
    return rows


def mirror(arch, m):
    """The mechanism's mirror image in the arch's axis (hinges keep their face)."""
    joints = tuple(arch.n - q for q in reversed(m.joints))
    return joints, tuple(reversed(m.sides))


def thrust_line(arch, spring, haunch, crown_side):
    """Symmetric thrust line through the right half's three hinges (lower bound).

    spring, haunch: (joint, side) of the right half's two lower hinges; crown_side: the
    side of the key block's right joint where the line passes. Returns P, H and, for each
    joint 0 .. key of the right half, (radius where the line crosses it, N, T): normal
    force (compression positive) and shear across the joint.
    """
    key = arch.key
    wk = arch.weight[key]
    xk, yk = arch.hinge[key][crown_side]
    # The key block pushes the right half with F = (H, -(P + wk) / 2) at (xk, yk). Across
    # joint m, the upper part (blocks m .. key-1 and F) pushes the lower part with
    # R = F + sum (0, -W_b), whose moment about the origin is M = xk Fy - yk Fx - sum W_b x_b;
    # R's line crosses joint m (unit direction u) at radius s where s (ux Ry - uy Rx) = M.
    # Both unknowns enter linearly: with V = (P + wk) / 2, each condition is
    # a_H H + a_V V = c.
    def condition(joint, side):
        ux, uy = math.cos(arch.angle[joint]), math.sin(arch.angle[joint])
        s = arch.inner if side == INTRADOS else arch.outer
        w = arch.sum_w[key] - arch.sum_w[joint]
        wx = arch.sum_wx[key] - arch.sum_wx[joint]
        # s (ux (-V - w) - uy H) = -xk V - yk H - wx
        return (-s * uy + yk, -s * ux + xk, s * ux * w - wx)

    a1, b1, c1 = condition(*spring)
    a2, b2, c2 = condition(*haunch)
    det = a1 * b2 - a2 * b1
    h = (c1 * b2 - c2 * b1) / det
    v = (a1 * c2 - a2 * c1) / det
    crossings = []
    for joint in range(key + 1):
        ux, uy = math.cos(arch.angle[joint]), math.sin(arch.angle[joint])
        w = arch.sum_w[key] - arch.sum_w[joint]
        wx = arch.sum_wx[key] - arch.sum_wx[joint]
        rx, ry = h, -v - w
        moment = xk * (-v) - yk * h - wx
        s = moment / (ux * ry - uy * rx)
        normal = -(rx * -uy + ry * ux)  # compression: R pushes the lower part backwards
        shear = rx * ux + ry * uy
        crossings.append((s, normal, shear))
    return 2.0 * v - wk, h, crossings


def symmetric_pair(arch, critical):
    """A critical mechanism from the right springing and its mirror image scaled to the
    same crown velocity, as block_velocities() fields: the symmetric motion; or None."""
    for m in critical:
        if m.joints[0] != 0:
            continue
        for n in critical:
            if (n.joints, n.sides) == mirror(arch, m):
                return [(m, 1.0), (n, m.load_work / n.load_work)]
    return None


def right_hinges(arch, critical):
    """The right half's three critical hinges (springing, haunch, key joint), or None."""
    right = sorted({h for m in critical for h in m.hinges() if h[0] <= arch.key})
    return right if len(right) == 3 and right[2][0] == arch.key else None


def symmetric_thrust_line(arch, critical):
    """The thrust line through the right half's critical hinges, or None."""
    right = right_hinges(arch, critical)
    return None if right is None else thrust_line(arch, right[0], right[1], right[2][1])


def check():
    ok = True

    def report(good, text):
        nonlocal ok
        ok &= good
        print(f"{'ok  ' if good else 'FAIL'} {text}")

    # 1. A symmetric arch: the critical mechanisms come in mirror pairs.
    arch = Arch(11, 1.8, 2.2)
    p, critical, _ = collapse(arch)
    keys = {(m.joints, m.sides) for m in critical}
    report(all(mirror(arch, m) in keys for m in critical),
           f"the {len(critical)} critical mechanisms of the example's arch come in mirror pairs")
    # 2. The thrust line through the critical hinges carries the same load inside the arch
    # (lower bound = upper bound: P_c is exact).
    line = symmetric_thrust_line(arch, critical)
    if line is None:
        report(False, "no symmetric thrust line through the critical hinges")
    else:
        p_line, _, crossings = line
        inside = all(arch.inner - 1e-9 <= r <= arch.outer + 1e-9 for r, _, _ in crossings)
        report(abs(p_line - p) <= 1e-9 * arch.total_weight() and inside,
               f"lower bound: a thrust line inside the arch carries P = {p_line:.3f} N/m "
               f"= P_c = {p:.3f} N/m")
    # 3. A critical mechanism plus its mirror image drops the key block without turning it,
    # and the finite-rotation slider-crank of that motion starts as virtual work says: under
    # a constant 1.5 P_c the crown falls a t^2 / 2 at first.
    pair = symmetric_pair(arch, critical)
    rates = [w for _, _, w in block_velocities(arch, pair)[0]]
    report(abs(rates[arch.key]) < 1e-12 * abs(rates[0]),
           "the symmetric motion (a critical mechanism plus its mirror image) drops the key "
           "block without turning it")
    a = crown_acceleration(arch, pair, 1.5 * p)
    spring, haunch, crown = right_hinges(arch, critical)
    fall = symmetric_fall(arch, spring, haunch, crown[1], lambda t: 1.5 * p, 0.01, dt=1e-4)[-1][1]
    report(abs(fall / (0.5 * a * 0.01 ** 2) - 1.0) < 1e-2,
           f"symmetric collapse from rest: fall in 0.01 s {fall:.4e} m = a t^2 / 2 with the "
           f"virtual-work acceleration a = {a:.4f} m/s^2")
    # 4. Milankovitch (1907): a semicircular arch carries its own weight down to
    # t/R = 0.1075 (R: centreline radius; Heyman's approximate value is 0.106). Hinges
    # only at joints can only make the arch stronger, so a fine arch of annular-sector
    # voussoirs must come out at or a little below it.
    t = minimum_thickness(30)
    report(0.1070 < t <= 0.1076, f"minimum thickness, 30 annular-sector voussoirs: t/R = "
           f"{t:.4f} (Milankovitch 0.1075)")
    # 5. Below that thickness the arch cannot stand (P_c < 0); above it, it can.
    thin = Arch(30, 0.95, 1.05, sectors=True)
    p_thin, _, stands = collapse(thin)
    report(p_thin < 0.0 and not stands, f"t/R = 0.10: P_c = {p_thin:.4g} N/m < 0")
    thick = Arch(30, 0.945, 1.055, sectors=True)
    p_thick, _, stands = collapse(thick)
    report(p_thick > 0.0 and stands, f"t/R = 0.11: P_c = {p_thick:.4g} N/m > 0")
    return ok


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--blocks", type=int, default=11, help="number of voussoirs (odd)")
    parser.add_argument("--inner", type=float, default=1.8, help="intrados radius (m)")
    parser.add_argument("--outer", type=float, default=2.2, help="extrados radius (m)")
    parser.add_argument("--density", type=float, default=2500.0, help="kg/m^3")
    parser.add_argument("--factor", type=float, default=1.5,
                        help="the load for the collapse motion, as a multiple of P_c")
    parser.add_argument("--ramp", type=float, default=0.1,
                        help="the load grows from 0 at t = 0 to full at this time (s)")
    parser.add_argument("--until", type=float, default=0.2, help="end of the collapse motion (s)")
    parser.add_argument("--check", action="store_true", help="run the self-checks")
    args = parser.parse_args()
    if args.check:
        sys.exit(0 if check() else 1)
    if args.blocks % 2 != 1:
        parser.error("--blocks must be odd (a key block at the crown)")
    arch = Arch(args.blocks, args.inner, args.outer, density=args.density)
    p, critical, stands = collapse(arch)
    total = arch.total_weight()
    radius = 0.5 * (arch.outer + arch.inner)
    print(f"arch: {arch.n} voussoirs, intrados {arch.inner} m, extrados {arch.outer} m, "
          f"t/R = {arch.thickness() / radius:.4f}, {args.density} kg/m^3")
    print(f"weight {total:.1f} N/m, key block {arch.weight[arch.key]:.1f} N/m; "
          f"load at the crown ({arch.crown[0]:.4f}, {arch.crown[1]:.4f})")
    if not stands:
        print("the arch cannot carry its own weight")
        return
    print(f"\ncollapse load P_c = {p:.1f} N/m = {p / total:.4f} x the arch's weight "
          f"({0.7 * p:.1f} N/m at 0.7 P_c, {args.factor * p:.1f} N/m at {args.factor} P_c)")
    print("\ncritical mechanisms (hinges at joint, side; joint k at 180 k / n degrees "
          "from the right springing):")
    for m in critical:
        print(f"  {m.describe()}")
    hinges = sorted({h for m in critical for h in m.hinges()})
    print("\nhinges of the collapse state (each critical mechanism uses four of them):")
    for joint, side in hinges:
        x, y = arch.hinge[joint][side]
        print(f"  joint {joint:2d}  {math.degrees(arch.angle[joint]):5.1f} deg  "
              f"{SIDE[side]:8s}  ({x:8.4f}, {y:8.4f})")
    line = symmetric_thrust_line(arch, critical)
    if line is not None:
        p_line, h, crossings = line
        print(f"\nthrust line through them (lower bound): P = {p_line:.1f} N/m, "
              f"horizontal thrust H = {h:.1f} N/m")
        print("  joint  angle   crosses at r   N (N/m)     T (N/m)   friction needed")
        for joint, (r, normal, shear) in enumerate(crossings):
            need = math.degrees(math.atan2(abs(shear), normal))
            print(f"  {joint:3d}   {math.degrees(arch.angle[joint]):5.1f}   {r:9.4f}   "
                  f"{normal:10.1f}  {shear:10.1f}   {need:5.1f} deg")
    pair, right = symmetric_pair(arch, critical), right_hinges(arch, critical)
    if pair is None or right is None:
        return
    m = pair[0][0]
    a = crown_acceleration(arch, pair, args.factor * p)
    # The turning rates of the right half's two bodies in the symmetric motion.
    rates = [w for _, _, w in block_velocities(arch, pair)[0]]
    below, above = rates[right[0][0]], rates[right[1][0]]
    print(f"\nsymmetric collapse ({m.describe()} with its mirror image): the key block drops "
          f"without turning, the blocks above the haunch hinge turn {abs(above / below):.3f} "
          f"times as fast as those below it; from rest at {args.factor} P_c the crown "
          f"accelerates at {a:.3f} m/s^2")
    ramp = args.ramp

    def load(t):
        return args.factor * p * (min(1.0, t / ramp) if ramp > 0.0 else 1.0)

    rows = symmetric_fall(arch, right[0], right[1], right[2][1], load, args.until)
    step = max(1, int(round(0.02 / 2e-4)))
    print(f"rigid blocks, finite rotations, load {args.factor} P_c ramped in over {ramp} s: "
          f"crown fall (mm) at")
    print("  " + "  ".join(f"{t:.2f} s: {1e3 * fall:.2f}" for t, fall in rows[step - 1::step]))


if __name__ == "__main__":
    main()
