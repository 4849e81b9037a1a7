#!/usr/bin/env python3
"""Issue 35: what the rises of ∫ γ dA in the anisotropic dumbbell's re-triangulation steps are, under refinement.

The adaptive τ rejects every flow step that raises the discrete energy E_h = Σ_f γ(a_f), but a
re-triangulation step changes the triangles E_h sums over: the remeshing places its vertices on the
smooth (Phong) surface the old triangles sample, its sizing rule may ask for another density than the
surface had, and the run then gives the body its volume back by a uniform normal offset. The sample
`anisotropic_dumbbell` (γ = √(4n₁² + n₂² + n₃²), the dumbbell of `shape dumbbell --edges-per-radius 4`
at edge length h, re-triangulated at ℓ = its mean edge) is measured at h = 0.5 (the sample's mesh),
0.5/√2 and 0.25, at three times: its first step (t = 0, where the sample's run re-triangulates) and at
t₀ = 0.5 and 0.9, reached with the sample's settings. From each surface one step is taken twice, the
same τ: without re-triangulation, and with a re-triangulation forced (`always`). The difference is the
re-triangulation's change of E_h, split into the remeshing's (the same step without the restoration)
and the restoration's; the same with the remeshing projecting onto the flat triangles
(`curved_projection = false`) is beside it. At t = 0 the remeshing's part is split further: the
pipeline with the isotropic sizing rule that made the input mesh (`sdflow.retriangulate`,
4 edges per radius) against the run's weighted-curvature rule, each at the input's volume (the
restoration's uniform offset along the eq. 8 normals, done here).

The tables go between "<!-- tables: anisotropic-remesh-energy -->" and
"<!-- end of tables: anisotropic-remesh-energy -->" in docs/validation.md (--print only prints them).

    PYTHONPATH=build/release/python scripts/anisotropic-remesh-energy.py [--edge-lengths 0.5,0.35355,0.25]
        [--times 0,0.5,0.9] [--doc docs/validation.md] [--print]
"""
import argparse
import math
import os
import subprocess
import sys

import numpy as np
import sdflow

HERE = os.path.dirname(os.path.abspath(__file__))
G = [4.0, 1.0, 1.0]  # samples/anisotropic_dumbbell.toml
ENERGY = {"kind": "ellipsoidal", "g": G}


def energy(V, F):
    """E_h = Σ_f γ(a_f), a_f the area vector of face f (docs/method.md, "The discrete energy")."""
    V, F = np.asarray(V), np.asarray(F)
    a = 0.5 * np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]])
    return float(np.sqrt((a * a * np.array(G)).sum(axis=1)).sum())


def restored(V, F, target):
    """V offset along its eq. 8 normals by the one distance that gives the volume `target` (flow/volume.h)."""
    V, F = np.asarray(V, dtype=float), np.asarray(F)
    N = np.asarray(sdflow.normals(V, F))
    offset = 0.0
    for _ in range(20):
        W = V + offset * N
        error = sdflow.volume(W, F) - target
        if abs(error) <= 1e-15 * abs(target):
            break
        a, b, c = W[F[:, 0]], W[F[:, 1]], W[F[:, 2]]
        rate = (np.cross(b, c) * N[F[:, 0]] + np.cross(c, a) * N[F[:, 1]] + np.cross(a, b) * N[F[:, 2]]).sum() / 6
        offset -= error / rate
    return V + offset * N


def one_step(V, F, ell, n, **retriangulation):
    """E_h, volume and vertex count after one step of the sample's flow from (V, F); re-triangulation forced."""
    flow = sdflow.Flow(V, F, conserve_volume=True, energy=ENERGY,
                       retriangulation=dict({"edge_length": ell, "edges_per_radius": n, "always": True}, **retriangulation))
    flow.step()
    return flow.metrics["energy"], flow.metrics["volume"], len(flow.V)


def surface_at(h, n, t0):
    """The sample's surface at t₀ with its input meshed at edge length h and n edges per radius, and the run's ℓ."""
    mesh = sdflow.shape("dumbbell", edge_length=h, edges_per_radius=n)
    V, F = np.asarray(mesh.V), np.asarray(mesh.F)
    ell = sdflow.mean_edge_length(V, F)  # the run's default ℓ
    if t0 > 0:
        # The first step re-triangulated, as the sample's run does at ℓ: the surface at t₀ is then sized
        # by the run's rule at every h, not by the isotropic one that made the input.
        first = sdflow.Flow(V, F, conserve_volume=True, energy=ENERGY,
                            retriangulation={"edge_length": ell, "edges_per_radius": n, "always": True})
        first.step()
        flow = sdflow.Flow(first.V, first.F, conserve_volume=True, energy=ENERGY,
                           retriangulation={"edge_length": ell, "edges_per_radius": n})
        flow.advance(t_end=t0 - first.t)
        V, F = flow.V, flow.F
    return V, F, ell


def measure(h, n, t0):
    V, F, ell = surface_at(h, n, t0)
    E0 = energy(V, F)
    flowed, _, _ = one_step(V, F, ell, n, enabled=False)
    total, _, count = one_step(V, F, ell, n)
    remeshed, volume, _ = one_step(V, F, ell, n, restore_volume=False)
    flat, _, _ = one_step(V, F, ell, n, curved_projection=False)
    flat_remeshed, flat_volume, _ = one_step(V, F, ell, n, curved_projection=False, restore_volume=False)
    V0 = sdflow.volume(V, F)
    row = {"t0": t0, "h": h, "n": n, "ell": ell, "E": E0, "before": len(V), "after": count, "flow": (flowed - E0) / E0,
           "total": (total - flowed) / E0, "remeshing": (remeshed - flowed) / E0, "restoration": (total - remeshed) / E0,
           "volume": (volume - V0) / V0, "flat": (flat - flowed) / E0, "flat_remeshing": (flat_remeshed - flowed) / E0,
           "flat_volume": (flat_volume - V0) / V0}
    if t0 == 0:
        # The input's own sizing rule (isotropic, 4 edges per radius) against the run's, each at the input's volume.
        iso = sdflow.retriangulate(V, F, edge_length=ell, edges_per_radius=n, curved_projection=True)
        W, H = np.asarray(iso.V), np.asarray(iso.F)
        row["iso_vertices"] = len(W)
        row["iso_remeshing"] = (energy(W, H) - E0) / E0
        row["iso_kept"] = (energy(restored(W, H, V0), H) - E0) / E0
    return row


def order(coarse, fine):
    """Observed order of |change| ≈ C ℓ^p between two rows."""
    if coarse["total"] == 0 or fine["total"] == 0 or coarse["total"] * fine["total"] < 0:
        return "–"
    return f"{math.log(abs(coarse['total'] / fine['total'])) / math.log(coarse['ell'] / fine['ell']):.1f}"


def observed_order(three):
    """Order p of E_h = E* − C ℓ^p from three inputs."""
    (a, b, c) = three
    return math.log((b["E"] - a["E"]) / (c["E"] - b["E"])) / math.log(a["ell"] / b["ell"])


def extrapolated(rows):
    """E* from the last three inputs of a series refined in ℓ and n together (Richardson at the observed order)."""
    a, b, c = rows[-3:]
    p = observed_order((a, b, c))
    return c["E"] + (c["E"] - b["E"]) / ((b["ell"] / c["ell"]) ** p - 1)


def tables(hs, times, series):
    """The rows of each series (n = 4 edges per radius, or n scaled with 1/h as well) at each t₀."""
    cases = [(h, 4.0 if kind == "fixed" else 4.0 * hs[0] / h) for kind in series for h in hs]
    rows = {t0: [measure(h, n, t0) for h, n in cases] for t0 in times}
    lines = ["| t₀ | n | ℓ | vertices | flow step | re-triangulation | remeshing (volume) | restoration | "
             "flat projection: re-triangulation; remeshing (volume) | order |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for t0 in times:
        for i, r in enumerate(rows[t0]):
            p = order(rows[t0][i - 1], r) if i % len(hs) else "–"
            lines.append(f"| {t0:g} | {r['n']:.3g} | {r['ell']:.3f} | {r['before']} → {r['after']} | {r['flow']:+.1e} | "
                         f"**{r['total']:+.1e}** | {r['remeshing']:+.1e} ({r['volume']:+.1e}) | {r['restoration']:+.1e} | "
                         f"{r['flat']:+.1e}; {r['flat_remeshing']:+.1e} ({r['flat_volume']:+.1e}) | {p} |")
    lines += ["", "| n | ℓ | E_h of the input | its deficit (E* − E_h)/E* | input's sizing rule: vertices; remeshing; "
              "at the input's volume | the run's rule: vertices; at the input's volume (the re-triangulation) |",
              "|---|---|---|---|---|---|"]
    first = rows[0.0] if 0.0 in rows else [measure(h, n, 0.0) for h, n in cases]
    for k in range(0, len(first), len(hs)):
        one_series = first[k:k + len(hs)]
        limit = extrapolated(one_series) if one_series[0]["n"] != one_series[-1]["n"] else None
        for r in one_series:
            deficit = f"{(limit - r['E']) / limit:.1e}" if limit else "–"
            lines.append(f"| {r['n']:.3g} | {r['ell']:.3f} | {r['E']:.3f} | {deficit} | {r['iso_vertices']}; "
                         f"{r['iso_remeshing']:+.1e}; {r['iso_kept']:+.1e} | {r['after']}; {r['total']:+.1e} |")
    if limit:
        lines += ["", f"E* = {limit:.3f}: the series refined in ℓ and n together, extrapolated from its last three inputs "
                  f"at their observed order {observed_order(first[-3:]):.2f} (Richardson)."]
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--edge-lengths", default=f"0.5,{0.5 / math.sqrt(2):.5f},0.25")
    parser.add_argument("--times", default="0,0.5,0.9")
    parser.add_argument("--series", default="fixed,scaled",
                        help="fixed: 4 edges per radius at every h; scaled: 4 h₀/h (h₀ the first edge length)")
    parser.add_argument("--doc", default=os.path.join(HERE, "..", "docs", "validation.md"))
    parser.add_argument("--print", action="store_true", help="print the tables, leave the doc alone")
    a = parser.parse_args()
    table = tables([float(x) for x in a.edge_lengths.split(",")], [float(x) for x in a.times.split(",")],
                   a.series.split(","))
    if a.print:
        print(table)
        return
    subprocess.run([sys.executable, os.path.join(HERE, "lib", "replace-doc-table.py"), a.doc, "anisotropic-remesh-energy"],
                   input=table, text=True, check=True)


if __name__ == "__main__":
    main()
