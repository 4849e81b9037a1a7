#!/usr/bin/env python3
"""Whether the substrate's energy W rises because of the time step or of the spatial discretisation.

The island of scripts/substrate-exact.py (`shape cuboid-island --a 1 --b 1 --c 0.5 --radius 0.45`,
η = 10, θ_Y = 60° and 120°, without the volume restoration) flows with the defaults to t₀ = 0.1,
0.3 and 1. From each of those surfaces it then takes constant steps of τ = 10⁻⁴, 10⁻⁵ and 10⁻⁶
over the same window t₀ → t₀ + 10⁻³, without re-triangulation, and W = ∫ γ dA − cos θ_Y A_base is measured after every
step. The continuous flow lowers W at the rate −∫ |∇μ|² dA − η ∮ (cos θ_d − cos θ_Y)² ds. A rise
that stays as τ falls, at a rate (W(t₀ + 10⁻³) − W(t₀)) / 10⁻³ that does not depend on τ, is the
semi-discrete scheme's, not the time step's.

The table goes between "<!-- tables: substrate-energy-rate -->" and
"<!-- end of tables: substrate-energy-rate -->" in docs/validation.md (--print only prints it).

    PYTHONPATH=build/release/python scripts/substrate-energy-rate.py [--edge-lengths 0.1,0.05]
        [--doc docs/validation.md] [--print]
"""
import argparse
import importlib.util
import math
import os
import subprocess
import sys

import sdflow

HERE = os.path.dirname(os.path.abspath(__file__))
_spec = importlib.util.spec_from_file_location("substrate_exact", os.path.join(HERE, "substrate-exact.py"))
substrate_exact = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(substrate_exact)

STARTS = (0.1, 0.3, 1.0)  # t₀: the island moving toward its cap, slowing, nearly there
WINDOW = 1e-3    # the time every constant τ covers
TAUS = (1e-4, 1e-5, 1e-6)
ANGLES = (60.0, 120.0)
SUBSTRATE = {"z": 0.0, "mobility": 10.0}


def energy(flow, sigma):
    """W = ∫ γ dA − σ A_base of the flow's surface."""
    return float(flow.metrics["energy"]) - sigma * substrate_exact.base_area(flow.V, flow.F)


def window(V, F, theta, tau):
    """W at the start and end of the window stepped at constant τ, and the steps in which W rose."""
    sigma = math.cos(math.radians(theta))
    flow = sdflow.Flow(V, F, boundary="substrate", conserve_volume=False, retriangulation=False,
                       substrate=dict(SUBSTRATE, contact_angle=theta), time_step="constant", tau=tau,
                       t_end=WINDOW)
    ws = [energy(flow, sigma)]

    def after(_step):
        ws.append(energy(flow, sigma))
        return False  # never stops the run

    flow.advance(callback=after)
    rises = sum(b > a + 1e-12 * abs(a) for a, b in zip(ws, ws[1:]))
    return ws[0], ws[-1], rises, len(ws) - 1


def case(theta, edge_length):
    """The surface at each t₀, then one window per τ from it: its rows of the table."""
    mesh = sdflow.shape("cuboid-island", a=1, b=1, c=0.5, radius=0.45, edge_length=edge_length)
    flow = sdflow.Flow(mesh.V, mesh.F, boundary="substrate", conserve_volume=False,
                       substrate=dict(SUBSTRATE, contact_angle=theta), t_end=STARTS[-1])
    rows = []
    for start_time in STARTS:
        flow.advance(t_end=start_time)
        V, F = flow.V, flow.F
        cells = []
        for tau in TAUS:
            try:
                start, end, rises, steps = window(V, F, theta, tau)
            except sdflow.NumericalError:  # τ above the mesh's stability limit: triangles turn over
                cells.append("unstable")
                continue
            cells.append(f"{rises} of {steps}; {(end - start) / (WINDOW * abs(start)):+.2e}")
        rows.append(f"| {theta:g}° | {edge_length:g} | {V.shape[0]} | {start_time:g} | " + " | ".join(cells) + " |")
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--edge-lengths", default="0.1,0.05")
    parser.add_argument("--doc", default=os.path.join(HERE, "..", "docs", "validation.md"))
    parser.add_argument("--print", action="store_true", help="print the table, leave the doc alone")
    a = parser.parse_args()
    lines = [f"#### W over t₀ → t₀ + {WINDOW:g} at constant τ from the island's adaptive run at t₀ (η = 10, no restoration, no re-triangulation in the window): steps in which W rose; (1/W) dW/dt over the window; \"unstable\" where the constant τ is above the mesh's stability limit",
             "",
             "| θ_Y | ℓ | vertices | t₀ | " + " | ".join(f"τ = {tau:g}" for tau in TAUS) + " |",
             "|---|---|---|---|" + "---|" * len(TAUS)]
    for theta in ANGLES:
        for h in (float(x) for x in a.edge_lengths.split(",")):
            lines += case(theta, h)
    table = "\n".join(lines) + "\n"
    if a.print:
        print(table)
        return
    subprocess.run([sys.executable, os.path.join(HERE, "lib", "replace-doc-table.py"), a.doc, "substrate-energy-rate"],
                   input=table, text=True, check=True)


if __name__ == "__main__":
    main()
