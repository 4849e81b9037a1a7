#!/usr/bin/env python3
"""An independent check of the 1-D reference (`sdflow axisymmetric`): the same flow, V = Δ_s H, on
surfaces of revolution, discretised differently and written without any of sdflow's code.

The reference solver moves the nodes of a generating polygon by parametric finite elements. This
one writes the generating curve as a function over a fixed grid and solves the flow's fourth-order
PDE for that function by conservative finite differences (the method of lines), integrated in time
by SciPy's implicit BDF with a sparse Jacobian:

  dumbbell  the radius as a graph over the axis, r(z, t), on 0 ≤ z ≤ Z: symmetric at z = 0 (the
            neck), clamped at z = Z, the equator of an end sphere that the flow does not reach in
            the time of the pinch-off. The grid is graded towards the neck.
  torus     the tube in polar coordinates about its centre circle, ρ(φ, t) with
            (r, z) = (R + ρ cos φ, ρ sin φ), on 0 ≤ φ ≤ π, symmetric at both ends (the outer and
            the inner equator). The grid is graded towards the inner equator, where the hole seals.

With H the mean curvature (the mean of the principal curvatures, positive on a sphere with the
outward normal) and ν the outward normal, a point of the curve moving along a fixed direction e
with speed u has normal speed V = u (e·ν), so u = V / (e·ν). The event is the time the smallest
distance to the axis reaches --until (a pinch-off or a seal); near it that distance falls as
(t* − t)^(1/4) (the self-similar approach of Bernoff, Bertozzi and Witelski 1998), so t* is
extrapolated by fitting r⁴ linearly in t over the last part of the approach.

  scripts/independent_reference.py dumbbell [--nodes N] [--radius 6 --neck-width 1 --separation 18]
  scripts/independent_reference.py torus [--nodes N] [--major 3 --minor 1.5]
Prints one JSON object: the shape, nodes, the event time at --until, the extrapolated t*, the
volume of the initial curve's body and its change up to the event, and the wall time.
"""
import argparse
import json
import math
import sys
import time

import numpy as np
from scipy import sparse
from scipy.integrate import solve_ivp


def central_derivatives(f, s_step):
    """First and second derivatives in the uniform parameter s, central differences, ghosts at
    both ends already in f (f has two more entries than the grid)."""
    first = (f[2:] - f[:-2]) / (2 * s_step)
    second = (f[2:] - 2 * f[1:-1] + f[:-2]) / s_step**2
    return first, second


class GradedGrid:
    """A smooth map x(s) of the uniform s ∈ [0, 1] onto [0, X] with nodes closer together, by the
    factor 1 − grading, at the end `fine_end` (0 or 1)."""

    def __init__(self, nodes, length, grading, fine_end):
        self.s_step = 1.0 / (nodes - 1)
        s = np.linspace(0, 1, nodes)
        # x = X (s − g sin(πs)/π) has x' = X (1 − g cos πs): smallest (1 − g) X at s = 0.
        sign = 1 if fine_end == 0 else -1
        self.x = length * (s - sign * grading * np.sin(np.pi * s) / np.pi)
        self.dx = length * (1 - sign * grading * np.cos(np.pi * s))
        self.ddx = length * sign * grading * np.pi * np.sin(np.pi * s)
        half = s[:-1] + self.s_step / 2
        self.dx_half = length * (1 - sign * grading * np.cos(np.pi * half))

    def derivatives(self, f_ghosted):
        """df/dx and d²f/dx² at the nodes."""
        fs, fss = central_derivatives(f_ghosted, self.s_step)
        fx = fs / self.dx
        return fx, (fss - self.ddx * fx) / self.dx**2

    def divergence(self, flux_half):
        """d(flux)/dx at the nodes from the flux at the midpoints, the flux odd about both ends
        (mirror planes; a clamped end's own value is not used)."""
        padded = np.concatenate(([-flux_half[0]], flux_half, [-flux_half[-1]]))
        return (padded[1:] - padded[:-1]) / (self.s_step * self.dx)


def mirror(f):
    """Ghost values of an even function at both ends of the grid."""
    return np.concatenate(([f[1]], f, [f[-2]]))


def midpoint_derivative(f, grid):
    return (f[1:] - f[:-1]) / (grid.s_step * grid.dx_half)


def dumbbell_profile(z, radius, neck_width, separation):
    """ρ(z) of the paper's dumbbell: ρ₀ + k z² on |z| ≤ t, the end circle beyond, C¹ at t
    (the same construction as shapes/dumbbell.h, solved again here by bisection)."""
    rho0, centre = neck_width / 2, separation / 2

    def mismatch(u):
        rho_t = math.sqrt(radius**2 - u**2)
        return 2 * rho_t * (rho_t - rho0) - (centre - u) * u

    lo, hi = 0.0, radius
    for _ in range(200):
        mid = (lo + hi) / 2
        if (mismatch(lo) > 0) == (mismatch(mid) > 0):
            lo = mid
        else:
            hi = mid
    u = (lo + hi) / 2
    join = centre - u
    k = (math.sqrt(radius**2 - u**2) - rho0) / join**2
    z = np.abs(z)
    cap = np.sqrt(np.maximum(radius**2 - (z - centre) ** 2, 0))
    return np.where(z <= join, rho0 + k * z**2, cap), join


def dumbbell_rhs(grid):
    def rhs(_, r):
        # r is the radius at nodes 0..N−1; node N−1 is clamped, its ghost mirrors r_z = 0 there.
        full = mirror(r)
        rz, rzz = grid.derivatives(full)
        q = np.sqrt(1 + rz**2)
        curvature = 0.5 * (1 / (r * q) - rzz / q**3)
        h = curvature
        r_half = 0.5 * (r[1:] + r[:-1])
        rz_half = (r[1:] - r[:-1]) / (grid.s_step * grid.dx_half)
        flux = r_half * midpoint_derivative(h, grid) / np.sqrt(1 + rz_half**2)
        velocity = grid.divergence(flux) / (r * q)
        drdt = velocity * q
        drdt[-1] = 0  # the clamped end
        return drdt

    return rhs


def polar_rhs(grid, major):
    def rhs(_, rho):
        full = mirror(rho)
        rp, rpp = grid.derivatives(full)
        phi = grid.x
        s_phi = np.sqrt(rho**2 + rp**2)
        r = major + rho * np.cos(phi)
        nu_r = (rp * np.sin(phi) + rho * np.cos(phi)) / s_phi
        meridian = (rho**2 + 2 * rp**2 - rho * rpp) / s_phi**3
        h = 0.5 * (meridian + nu_r / r)
        rho_half = 0.5 * (rho[1:] + rho[:-1])
        rp_half = (rho[1:] - rho[:-1]) / (grid.s_step * grid.dx_half)
        phi_half = 0.5 * (phi[1:] + phi[:-1])
        r_half = major + rho_half * np.cos(phi_half)
        flux = r_half * midpoint_derivative(h, grid) / np.sqrt(rho_half**2 + rp_half**2)
        velocity = grid.divergence(flux) / (r * s_phi)
        return velocity * s_phi / rho

    return rhs


def banded_sparsity(n, width=3):
    offsets = range(-width, width + 1)
    return sparse.diags([np.ones(n - abs(o)) for o in offsets], list(offsets), format="csc")


def trapezoid_volume(radius_of, axis_of, y):
    """π ∫ r² dz along the curve, by the trapezoidal rule on its nodes (for the volume drift)."""
    r, z = radius_of(y), axis_of(y)
    return abs(np.pi * np.sum(0.5 * (r[1:] ** 2 + r[:-1] ** 2) * np.diff(z)))


def evolve(rhs, y0, distance_to_axis, until, t_end, rtol):
    """Integrate to the time the smallest distance to the axis reaches `until`; returns that time,
    the samples (t, distance) of the approach and the final state."""

    def reached(t, y):
        return distance_to_axis(y) - until

    reached.terminal = True
    samples = []

    def watched(t, y):
        samples.append((t, distance_to_axis(y)))
        return rhs(t, y)

    solution = solve_ivp(watched, (0, t_end), y0, method="BDF", rtol=rtol, atol=rtol * 1e-3,
                         jac_sparsity=banded_sparsity(len(y0)), events=reached, dense_output=False)
    if solution.status != 1:
        raise SystemExit(f"independent_reference: no event before t = {t_end} ({solution.message})")
    event = float(solution.t_events[0][0])
    return event, samples, solution.y_events[0][0]


def extrapolate(samples, event, until):
    """t* from r⁴ linear in t over the approach below 3·until (the last samples the solver took)."""
    t = np.array([s[0] for s in samples])
    d = np.array([s[1] for s in samples])
    mask = (d < 3 * until) & (t <= event)
    if mask.sum() < 4:
        return event
    slope, intercept = np.polyfit(t[mask], d[mask] ** 4, 1)
    return float(-intercept / slope) if slope < 0 else event


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("shape", choices=["dumbbell", "torus"])
    parser.add_argument("--nodes", type=int, default=1200)
    parser.add_argument("--radius", type=float, default=6)
    parser.add_argument("--neck-width", type=float, default=1)
    parser.add_argument("--separation", type=float, default=18)
    parser.add_argument("--major", type=float, default=3)
    parser.add_argument("--minor", type=float, default=1.5)
    parser.add_argument("--grading", type=float, default=0.9, help="in [0, 1): how much finer the grid gets at the event")
    parser.add_argument("--until", type=float, default=0.03, help="distance to the axis that ends the run")
    parser.add_argument("--rtol", type=float, default=1e-7)
    parser.add_argument("--end-time", type=float, default=50)
    args = parser.parse_args()
    if not (args.nodes >= 20 and 0 <= args.grading < 1 and args.until > 0):
        parser.error("need --nodes ≥ 20, 0 ≤ --grading < 1, --until > 0")
    start = time.perf_counter()
    if args.shape == "dumbbell":
        if not (0 < args.neck_width / 2 < args.radius < args.separation / 2):
            parser.error("need 0 < neck width / 2 < radius < separation / 2")
        length = args.separation / 2  # the end sphere's equator
        grid = GradedGrid(args.nodes, length, args.grading, fine_end=0)
        y0, _ = dumbbell_profile(grid.x, args.radius, args.neck_width, args.separation)
        rhs = dumbbell_rhs(grid)
        distance = np.min
        # The evolving half-bodies up to the end spheres' equators, and the still hemispheres beyond.
        volume = lambda y: 2 * trapezoid_volume(lambda v: v, lambda v: grid.x, y) + 4 * np.pi * args.radius**3 / 3  # noqa: E731
    else:
        if not (0 < args.minor < args.major):
            parser.error("need 0 < minor < major")
        grid = GradedGrid(args.nodes, np.pi, args.grading, fine_end=1)
        y0 = np.full(args.nodes, args.minor)
        rhs = polar_rhs(grid, args.major)
        distance = lambda y: np.min(args.major + y * np.cos(grid.x))  # noqa: E731
        volume = lambda y: 2 * trapezoid_volume(lambda v: args.major + v * np.cos(grid.x),  # noqa: E731
                                                lambda v: v * np.sin(grid.x), y)
    event, samples, final = evolve(rhs, y0, distance, args.until, args.end_time, args.rtol)
    result = {
        "shape": args.shape,
        "nodes": args.nodes,
        "until": args.until,
        "event_time": event,
        "extrapolated_time": extrapolate(samples, event, args.until),
        "volume": volume(y0),
        "volume_change": volume(final) / volume(y0) - 1,
        "seconds": round(time.perf_counter() - start, 2),
    }
    json.dump(result, sys.stdout, indent=1)
    print()


if __name__ == "__main__":
    main()
