#!/usr/bin/env python3
"""Writes README's table of the anisotropic samples (between "<!-- anisotropic -->" and
"<!-- end of anisotropic -->") from their runs on disk, as `samples/reproduce.sh wulff_ellipsoid
cubic_faceting anisotropic_dumbbell` leaves them in runs/NAME. Each cell is read from the
run's metrics.csv (and, for the Wulff shape, its last snapshot); a run not on disk says "not run".

For every run: steps and final time, the energy ∫ γ dA at the start and end, how many flow steps
raised it (by more than 10⁻¹² relative; steps that re-triangulated are counted apart, a remeshing
changes the discrete energy without the flow), the material volume's drift, the curvature deviation
(of μ) at the start and end, and the first topology change. For `wulff_ellipsoid`, the semi-axes
of the ellipsoid fitted to the last snapshot against the Wulff shape of the run's volume.

    scripts/readme-anisotropic.py [--runs runs] [--readme README.md]
"""
import argparse
import csv
import glob
import importlib.util
import math
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
_spec = importlib.util.spec_from_file_location("wulff", os.path.join(HERE, "anisotropic-wulff.py"))
wulff = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(wulff)

SAMPLES = [
    ("wulff_ellipsoid", "√(n₁² + n₂² + 4n₃²)", "a unit sphere relaxes to its Wulff shape, the ellipsoid ∝ (1, 1, 2)"),
    ("cubic_faceting", "Σ_l √(n_l² + 0.1 Σ_{k≠l} n_k²)", "a unit sphere facets into a rounded cube"),
    ("anisotropic_dumbbell", "√(4n₁² + n₂² + n₃²)", "the paper's dumbbell: the neck pinches off, then the ends begin to relax toward ellipsoids"),
]
RETRIANGULATING = re.compile(r"remeshed|surgery|cleaned|split|merged")


def measure(run):
    path = os.path.join(run, "metrics.csv")
    if not os.path.exists(path):
        return "not run"
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    first, last = rows[0], rows[-1]
    rises, remesh_rises, largest = 0, 0, 0.0
    event = ""
    for before, after in zip(rows, rows[1:]):
        e0, e1 = float(before["energy"]), float(after["energy"])
        if e1 > e0 * (1 + 1e-12):
            if RETRIANGULATING.search(after["event"]):
                remesh_rises += 1
            else:
                rises += 1
                largest = max(largest, e1 / e0 - 1)
        if not event and (after["components"] != before["components"] or after["genus"] != before["genus"]):
            kind = "bodies" if after["components"] != before["components"] else "genus"
            a, b = (before["components"], after["components"]) if kind == "bodies" else (before["genus"], after["genus"])
            event = f"{a} → {b} {kind} at t = {float(after['time']):.4g}"
    e0, e1 = float(first["energy"]), float(last["energy"])
    volume0 = float(first["volume"]) + float(first["debris_volume"] or 0)
    volume1 = float(last["volume"]) + float(last["debris_volume"] or 0)
    cell = (f"{last['step']} steps to t = {float(last['time']):.4g}; energy {e0:.5g} → {e1:.5g} "
            f"({100 * (e1 / e0 - 1):+.2f}%), rose in {rises} flow step{'s' if rises != 1 else ''}")
    if rises:
        cell += f" (at most {largest:.1e})"
    if remesh_rises:
        cell += f" and {remesh_rises} re-triangulation{'s' if remesh_rises != 1 else ''}"
    cell += (f"; volume {100 * (volume1 / volume0 - 1):+.1e}%; μ deviation "
             f"{float(first['curvature_deviation_pct']):.3g}% → {float(last['curvature_deviation_pct']):.3g}%")
    if event:
        cell += f"; {event}"
    return cell


def wulff_cell(run, g):
    snapshots = sorted(glob.glob(os.path.join(run, "snapshots", "step_*.ply")))
    if not snapshots:
        return "not run"
    with open(os.path.join(run, "metrics.csv"), newline="") as f:
        volume = float(next(csv.DictReader(f))["volume"])
    scale = (3 * volume / (4 * math.pi * math.sqrt(g[0] * g[1] * g[2]))) ** (1 / 3)
    exact = [scale * math.sqrt(x) for x in g]
    fitted = wulff.fitted_semi_axes(wulff.read_ply_vertices(snapshots[-1]))
    error = max(abs(a / b - 1) for a, b in zip(fitted, exact))
    return (f"semi-axes {', '.join(f'{a:.4f}' for a in fitted)} against the Wulff shape's "
            f"{', '.join(f'{b:.4f}' for b in exact)}: {100 * error:.2f}% at most")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", default=os.path.join(HERE, "..", "runs"))
    parser.add_argument("--readme", default=os.path.join(HERE, "..", "README.md"))
    args = parser.parse_args()
    lines = ["| scenario | γ(n) | what happens | measured |", "|---|---|---|---|"]
    for name, gamma, what in SAMPLES:
        cell = measure(os.path.join(args.runs, name))
        if name == "wulff_ellipsoid" and cell != "not run":
            cell += "; " + wulff_cell(os.path.join(args.runs, name), (1, 1, 4))
        lines.append(f"| `{name}` | {gamma} | {what} | {cell} |")
    with open(args.readme) as f:
        text = f.read()
    begin, end = "<!-- anisotropic -->\n", "<!-- end of anisotropic -->"
    if begin not in text or end not in text:
        sys.exit(f"readme-anisotropic: {args.readme} lacks the markers {begin.strip()} and {end}")
    head, rest = text.split(begin, 1)
    _, tail = rest.split(end, 1)
    new = head + begin + "\n".join(lines) + "\n" + end + tail
    tmp = args.readme + ".tmp"
    with open(tmp, "w") as f:
        f.write(new)
    os.replace(tmp, args.readme)
    print("\n".join(lines))


if __name__ == "__main__":
    main()
