#!/usr/bin/env python3
"""Issue 35's linear-rate check: how fast a slightly perturbed Wulff shape returns to it, under refinement.

A Wulff ellipsoid of γ = √(nᵀ diag(g) n) (`sdflow.shape("ellipsoid")` with semi-axes √g) is
perturbed radially by ε Y, Y = 3 u_z² − 1 on the Wulff-normalised directions u = x/√g, ε = 10⁻³, and
flows without re-triangulation, volume conserved, at a constant τ. Its amplitude a(t) is the
area-weighted projection of ρ − 1 on Y, where ρ = √(xᵀ diag(g)⁻¹ x) / r and r is the Wulff scale of
the volume. The same mesh unperturbed flows beside it and its amplitude is subtracted, so that the
discrete shape's own distance from the exact Wulff shape does not enter. The rate is
λ = ln(δa(t1) / δa(t2)) / (t2 − t1), late enough that the faster modes in Y's discrete projection are
gone; at τ and τ/2, extrapolated to τ → 0 (first order in τ).
For g = (1, 1, 1) the Wulff shape is the sphere, Y its l = 2 harmonic and the exact rate 12 / r⁴: those
rows check the measurement itself. For an anisotropic g there is no closed form; the rows give the
rate's change between resolutions and the observed order of those changes in h ∝ 1/√vertices.

    scripts/anisotropic-rates.py [--vertices 650,2500,10000] [--g 1,2,3] [--tau 2.5e-4]
                                 [--window 0.05,0.15]
Needs the Python module on PYTHONPATH (build/release/python, -DSDFLOW_BUILD_PYTHON=ON).
"""
import argparse
import math

import numpy as np
import sdflow

EPSILON = 1e-3


def amplitude(V, F, g, r, Y):
    """Area-weighted projection of ρ − 1 on Y."""
    areas = sdflow.vertex_areas(V, F)
    X = V - V.mean(axis=0)
    rho = np.sqrt((X**2 / g).sum(axis=1)) / r
    return float((areas * (rho - 1) * Y).sum() / (areas * Y * Y).sum())


def rate(V, F, Y, g, tau, window):
    """λ between the window's two times, from the perturbed run less the unperturbed one."""
    energy = {"kind": "isotropic"} if (g == 1).all() else {"kind": "ellipsoidal", "g": [float(x) for x in g]}
    amplitudes = []
    for epsilon in (EPSILON, 0.0):
        W = V * (1 + epsilon * Y)[:, None]
        r = (sdflow.volume(W, F) / (4 * math.pi / 3 * math.sqrt(g.prod()))) ** (1 / 3)
        flow = sdflow.Flow(W, F, retriangulation=False, conserve_volume=True, time_step="constant", tau=tau,
                           energy=energy, t_end=window[1])
        values = []
        for t in window:
            flow.advance(t_end=t)
            values.append(amplitude(flow.V, flow.F, g, r, Y))
        amplitudes.append((values, r))
    (perturbed, r), (unperturbed, _) = amplitudes
    d = [a - b for a, b in zip(perturbed, unperturbed)]
    return math.log(d[0] / d[1]) / (window[1] - window[0]), r


def row(vertices, g, tau, window):
    V, F = sdflow.shape("ellipsoid", vertices=vertices, a=math.sqrt(g[0]), b=math.sqrt(g[1]), c=math.sqrt(g[2]))
    V, F = np.asarray(V), np.asarray(F)
    U = V / np.sqrt(g)
    U /= np.linalg.norm(U, axis=1)[:, None]
    Y = 3 * U[:, 2] ** 2 - 1
    coarse, r = rate(V, F, Y, g, tau, window)
    fine, _ = rate(V, F, Y, g, tau / 2, window)
    return {"vertices": len(V), "coarse": coarse, "fine": fine, "extrapolated": 2 * fine - coarse, "r": r}


def order(e_coarse, e_fine, n_coarse, n_fine):
    """Observed order of e ≈ C h^p with h ∝ 1/√vertices."""
    if e_coarse == 0 or e_fine == 0:
        return float("nan")
    return math.log(abs(e_coarse / e_fine)) / (0.5 * math.log(n_fine / n_coarse))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--vertices", default="650,2500,10000")
    parser.add_argument("--g", default="1,2,3")
    parser.add_argument("--tau", type=float, default=2.5e-4)
    parser.add_argument("--window", default="0.05,0.15")
    a = parser.parse_args()
    resolutions = [int(v) for v in a.vertices.split(",")]
    window = [float(t) for t in a.window.split(",")]
    print(f"| g | vertices | λ at τ = {a.tau:g} | at τ/2 | τ → 0 | against | difference | order |")
    print("|---|---|---|---|---|---|---|---|")
    for g in (np.ones(3), np.array([float(x) for x in a.g.split(",")])):
        rows = [row(n, g, a.tau, window) for n in resolutions]
        isotropic = (g == 1).all()
        for i, rw in enumerate(rows):
            if isotropic:
                reference, label = 12 / rw["r"] ** 4, f"exact 12/r⁴ = {12 / rw['r'] ** 4:.5f}"
                error = rw["extrapolated"] / reference - 1
                p = order(rows[i - 1]["extrapolated"] / (12 / rows[i - 1]["r"] ** 4) - 1, error,
                          rows[i - 1]["vertices"], rw["vertices"]) if i else float("nan")
            else:
                if i + 1 == len(rows):
                    label, error, p = "–", float("nan"), float("nan")
                else:
                    nxt = rows[i + 1]
                    label = f"next finer ({nxt['vertices']})"
                    error = rw["extrapolated"] / nxt["extrapolated"] - 1
                    p = float("nan")
                    if i + 2 < len(rows):
                        change_next = nxt["extrapolated"] / rows[i + 2]["extrapolated"] - 1
                        p = order(error, change_next, rw["vertices"], nxt["vertices"])
            gs = "(" + ", ".join(f"{x:g}" for x in g) + ")"
            err = "–" if math.isnan(error) else f"{100 * error:+.3f}%"
            ps = "–" if math.isnan(p) else f"{p:.2f}"
            print(f"| {gs} | {rw['vertices']} | {rw['coarse']:.5f} | {rw['fine']:.5f} | {rw['extrapolated']:.5f} | "
                  f"{label} | {err} | {ps} |", flush=True)


if __name__ == "__main__":
    main()
