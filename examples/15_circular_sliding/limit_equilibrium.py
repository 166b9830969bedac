#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The right answers of examples/15_circular_sliding: a rigid mass on a circular slip surface.

The sliding mass is the polygon between the slip surface (the polyline of slope.geo: n
chords with their ends on the circle of radius R about O) and the slope's surface (the
toe T, the crest, the point C where the circle meets the top). A rigid body touching a
circle along an arc can move in one way only: turning about the circle's centre O. Plain
Python 3, no numpy. It prints:

1. The mass: area A, centroid G, polar moment J_O about O, the lever d = x_O - x_G of its
   weight W = rho g A about O (the weight turns it counter-clockwise, towards the valley).

2. Without friction (case_frictionless.toml): every contact force passes through O, so
   the mass is a pendulum about O: J_O theta'' = -g A (x_G(theta) - x_O) (per unit
   density), from rest: theta'' = g A d / J_O at the start. The script integrates it
   (RK4) and prints theta(t) and the centroid's path.

3. With friction angle phi: the limits of the critical friction angle (case.toml slides,
   case_stands.toml stands). When the mass turns, every point of the arc slides, so the
   contact force on it is inclined at phi to the normal (towards O), against the motion:
   its line passes at R sin(phi) from O (Taylor's friction circle). With N the sum of the
   normal forces and c their mean direction (|c| <= 1, a positive mean of the unit normals,
   which fan out over the arc's angle 2 beta), the resultant is N / cos(phi) |c| long,
   and its moment about O is R tan(phi) N. At the onset of turning it balances the weight:
   resultant W (vertical), moment W d. So

       d = K R sin(phi),   K = 1 / |c| >= 1,

   and the direction of c is fixed: vertical turned by phi. The normal stress along the
   arc (which a rigid-body statics cannot tell) sets K between 1 (all of N at one point)
   and K_max = cos(gamma) / cos(beta) (all of it at the two ends of the arc; gamma the
   angle from c to the middle of the fan). Hence:
     - sin(phi) >= d / R: no distribution can turn the mass: it stands (phi_u below);
     - sin(phi) < d / (K_max R): no distribution can hold it: it slides (phi_l below);
     - between the two, it depends on the normal stress along the arc.
   For comparison the script also gives the friction angle at which the textbook methods
   of slices (vertical slices, dry, no cohesion) give a factor of safety of 1: Fellenius
   (normal force W cos(alpha) on each slice) and Bishop's simplified method (vertical
   equilibrium of each slice, moment equilibrium of the whole).

Run: python3 limit_equilibrium.py [--time T]  (the pendulum's motion up to T s; default 1)
"""

import argparse
import math

# slope.geo's parameters.
XO, YO = 20.0, 30.0      # centre of the slip circle
TOE = (22.0, 5.0)
CREST = (14.0, 15.0)
TOP = 15.0               # the top surface y = 15
N_CHORDS = 101
G = 9.81


def slip_polyline():
    """The polyline's vertices from C (on the top surface) to the toe, as slope.geo makes them."""
    r = math.hypot(TOE[0] - XO, TOE[1] - YO)
    xc = XO - math.sqrt(r * r - (TOP - YO) ** 2)
    a0 = math.atan2(TOP - YO, xc - XO) % (2.0 * math.pi)
    a1 = math.atan2(TOE[1] - YO, TOE[0] - XO) + 2.0 * math.pi
    da = (a1 - a0) / N_CHORDS
    return r, a0, a1, [(XO + r * math.cos(a0 + k * da), YO + r * math.sin(a0 + k * da))
                       for k in range(N_CHORDS + 1)]


def polygon_properties(points):
    """Area, centroid and polar second moment about the origin of a counter-clockwise polygon."""
    a = cx = cy = ixx = iyy = 0.0
    for (x0, y0), (x1, y1) in zip(points, points[1:] + points[:1]):
        cross = x0 * y1 - x1 * y0
        a += cross
        cx += (x0 + x1) * cross
        cy += (y0 + y1) * cross
        ixx += (y0 * y0 + y0 * y1 + y1 * y1) * cross
        iyy += (x0 * x0 + x0 * x1 + x1 * x1) * cross
    a *= 0.5
    return a, (cx / (6.0 * a), cy / (6.0 * a)), (ixx + iyy) / 12.0


def sliding_mass():
    r, a0, a1, arc = slip_polyline()
    # C -> along the arc (counter-clockwise about O, i.e. down and to the right) -> toe ->
    # crest -> back to C along the top: counter-clockwise around the mass.
    points = [(x - XO, y - YO) for x, y in arc + [CREST]]
    area, (gx, gy), polar_o = polygon_properties(points)
    assert area > 0.0
    return dict(radius=r, a0=a0, a1=a1, arc=arc, area=area, centroid=(XO + gx, YO + gy),
                polar=polar_o, lever=-gx)


def pendulum(mass, until, dt=1e-4):
    """theta(t) of the rigid mass turning about O without friction, from rest (RK4)."""
    gx, gy = mass["centroid"][0] - XO, mass["centroid"][1] - YO
    rg, psi = math.hypot(gx, gy), math.atan2(gy, gx)
    k = G * mass["area"] / mass["polar"]

    def accel(theta):  # counter-clockwise positive; the weight's moment about O
        return -k * rg * math.cos(psi + theta)

    theta, omega, t, out = 0.0, 0.0, 0.0, [(0.0, 0.0, 0.0)]
    while t < until - 1e-12:
        h = min(dt, until - t)
        k1 = (omega, accel(theta))
        k2 = (omega + h / 2 * k1[1], accel(theta + h / 2 * k1[0]))
        k3 = (omega + h / 2 * k2[1], accel(theta + h / 2 * k2[0]))
        k4 = (omega + h * k3[1], accel(theta + h * k3[0]))
        theta += h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
        omega += h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
        t += h
        out.append((t, theta, omega))
    return out


def friction_limits(mass):
    r, a0, a1, d = mass["radius"], mass["a0"], mass["a1"], mass["lever"]
    beta = 0.5 * (a1 - a0)
    bisector = 0.5 * (a0 + a1) + math.pi   # the middle of the fan of inward normals

    def k_max(phi):
        gamma = (math.pi / 2 - phi) - bisector
        gamma = (gamma + math.pi) % (2 * math.pi) - math.pi
        return math.cos(gamma) / math.cos(beta) if abs(gamma) <= beta else math.inf

    phi_u = math.asin(d / r)
    lo, hi = 0.0, phi_u
    for _ in range(80):   # sin(phi) K_max(phi) R = d
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if math.sin(mid) * k_max(mid) * r < d else (lo, mid)
    return math.degrees(lo), math.degrees(phi_u), k_max(lo), beta


def sliding_acceleration(mass, phi):
    """Bounds on the angular acceleration (rad/s^2) with which the mass starts to turn from rest
    when the friction angle phi (radians) is below the critical one.

    Turning about O at alpha, the centroid accelerates at a_G = alpha z x (G - O); the arc's
    reaction is F = M a_G + W (upwards) and, as above, its moment about O is K R sin(phi) |F|,
    K between 1 and K_max (of F's direction turned by phi). J_O alpha = W d - K R sin(phi) |F|
    is solved for alpha with K = 1 (the largest alpha) and K = K_max (the smallest);
    everything per unit density and thickness.
    """
    r, a0, a1 = mass["radius"], mass["a0"], mass["a1"]
    beta, bisector = 0.5 * (a1 - a0), 0.5 * (a0 + a1) + math.pi
    gx, gy = mass["centroid"][0] - XO, mass["centroid"][1] - YO
    w, d, j = G * mass["area"], mass["lever"], mass["polar"]

    def reaction(alpha):
        return mass["area"] * alpha * -gy, w + mass["area"] * alpha * gx

    def k_max(alpha):
        fx, fy = reaction(alpha)
        gamma = math.atan2(fy, fx) - phi - bisector
        gamma = (gamma + math.pi) % (2 * math.pi) - math.pi
        return math.cos(gamma) / math.cos(beta) if abs(gamma) <= beta else math.inf

    def solve(k_of):
        lo, hi = 0.0, w * d / j
        for _ in range(80):
            mid = 0.5 * (lo + hi)
            excess = w * d - k_of(mid) * r * math.sin(phi) * math.hypot(*reaction(mid)) - j * mid
            lo, hi = (mid, hi) if excess > 0 else (lo, mid)
        return lo

    return solve(k_max), solve(lambda alpha: 1.0)


def slices(mass, count=400):
    """(weight, base inclination) of vertical slices of the mass (per unit rho g)."""
    arc = mass["arc"]
    x_left, x_right = arc[0][0], arc[-1][0]

    def surface(x):   # top of the mass: the top surface, then the slope face
        if x <= CREST[0]:
            return TOP
        return CREST[1] + (x - CREST[0]) * (TOE[1] - CREST[1]) / (TOE[0] - CREST[0])

    def base(x):      # the polyline under x, and its inclination (positive: down to the right)
        for (x0, y0), (x1, y1) in zip(arc, arc[1:]):
            if x0 <= x <= x1:
                return y0 + (x - x0) * (y1 - y0) / (x1 - x0), math.atan2(y0 - y1, x1 - x0)
        raise ValueError(x)

    out, h = [], (x_right - x_left) / count
    for i in range(count):
        x = x_left + (i + 0.5) * h
        y, alpha = base(x)
        out.append(((surface(x) - y) * h, alpha))
    return out


def critical_phi(factor_of_safety):
    lo, hi = 1e-6, math.radians(60)
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if factor_of_safety(mid) < 1.0 else (lo, mid)
    return math.degrees(lo)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--time", type=float, default=1.0, help="pendulum motion up to (s)")
    args = parser.parse_args()
    m = sliding_mass()
    gx, gy = m["centroid"]
    print(f"slip circle: O = ({XO}, {YO}), R = {m['radius']:.6f} m, arc from "
          f"{math.degrees(m['a0']):.3f} to {math.degrees(m['a1']):.3f} degrees "
          f"({N_CHORDS} chords of {2 * m['radius'] * math.sin((m['a1'] - m['a0']) / (2 * N_CHORDS)):.4f} m)")
    print(f"sliding mass: area {m['area']:.6f} m^2, centroid G = ({gx:.6f}, {gy:.6f}), "
          f"J_O = {m['polar']:.4f} m^4, lever d = x_O - x_G = {m['lever']:.6f} m, "
          f"|OG| = {math.hypot(gx - XO, gy - YO):.6f} m")

    print("\nwithout friction: a pendulum about O")
    alpha0 = G * m["area"] * m["lever"] / m["polar"]
    print(f"  initial angular acceleration g A d / J_O = {alpha0:.6f} rad/s^2 (counter-clockwise)")
    motion = pendulum(m, args.time)
    rg, psi = math.hypot(gx - XO, gy - YO), math.atan2(gy - YO, gx - XO)
    for t, theta, omega in motion[:: max(1, len(motion) // 10)] + [motion[-1]]:
        ux = XO + rg * math.cos(psi + theta) - gx
        uy = YO + rg * math.sin(psi + theta) - gy
        print(f"  t = {t:6.3f} s  theta = {theta:.6f} rad  omega = {omega:.6f} rad/s  "
              f"G moved ({ux:+.6f}, {uy:+.6f}) m, {m['radius'] * theta:.6f} m along the arc")

    print("\nwith friction: the critical friction angle of the rigid mass")
    phi_l, phi_u, k_max, beta = friction_limits(m)
    print(f"  arc half-angle beta = {math.degrees(beta):.3f} degrees")
    print(f"  phi_u = asin(d / R) = {phi_u:.3f} degrees: above it the mass stands whatever the "
          f"normal stress")
    print(f"  phi_l = {phi_l:.3f} degrees (K_max = {k_max:.4f}): below it the mass slides "
          f"whatever the normal stress")
    parts = slices(m)
    driving = sum(w * math.sin(a) for w, a in parts)
    fellenius = critical_phi(lambda p: sum(w * math.cos(a) for w, a in parts) * math.tan(p)
                             / driving)

    def bishop(p):
        fs = 1.0
        for _ in range(200):
            fs = sum(w * math.tan(p) / (math.cos(a) + math.sin(a) * math.tan(p) / fs)
                     for w, a in parts) / driving
        return fs
    for phi in (17.0,):
        low, high = sliding_acceleration(m, math.radians(phi))
        print(f"  phi = {phi} degrees: it starts to turn at {low:.5f} to {high:.5f} rad/s^2, "
              f"theta = {0.5 * low:.6f} to {0.5 * high:.6f} rad after 1 s at that rate")
    print(f"  methods of slices, factor of safety 1 at: Fellenius {fellenius:.3f} degrees, "
          f"Bishop (simplified) {critical_phi(bishop):.3f} degrees")


if __name__ == "__main__":
    main()
