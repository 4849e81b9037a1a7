#!/usr/bin/env python3
"""Writes README's table of the substrate samples (between "<!-- substrate -->" and
"<!-- end of substrate -->") from their runs on disk, as `sdflow run samples/NAME.toml` (or
`samples/reproduce.sh NAME`) leaves them in runs/NAME; a run not on disk says "not run".

For every run: how it ended (finished, or the error it stopped with), steps, final time and
vertices; the islands (components) and contact lines (boundary loops) at the start and the end, and
each topology change on the way (metrics.csv's components and its touchdown and contact events);
the material volume's drift; the contact line's largest distance from the plane on the last snapshot
and its shortest and longest edge, in units of the run's ℓ, on the first and last. For the
relaxing islands, the last snapshot's height and base radius against the exact equilibrium of the
run's volume (the spherical cap of θ_Y, or the Winterbottom shape of an ellipsoidal γ; see
scripts/substrate-exact.py).

    scripts/readme-substrate.py [--runs runs] [--readme README.md]
"""
import argparse
import csv
import glob
import importlib.util
import math
import os
import re
import sys
import tomllib

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
_spec = importlib.util.spec_from_file_location("exact", os.path.join(HERE, "substrate-exact.py"))
exact = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(exact)

SAMPLES = [
    ("island_on_substrate", "a 2 × 1 × 0.5 box, θ_Y = 60°: relaxes to the spherical cap of its volume", True),
    ("winterbottom_island", "a rounded 1 × 1 × 0.5 box, γ = √(n₁² + n₂² + 4n₃²), σ = ½: relaxes to its Winterbottom shape", True),
    ("island_breakup", "a ridge 8 × 1 × 0.5 (ends rounded), θ_Y = 90°, η = 10: thins in its middle and breaks into islands", False),
    ("film_with_hole", "a 6 × 6 film 0.5 thick with a hole of radius 1, θ_Y = 120°, η = 1: dewets from its hole and its outer edge", False),
    ("film_rim_breakup", "a 6 × 6 film 0.5 thick with a hole of radius 2.5, θ_Y = 120°, η = 1: the ring of film left retracts and breaks where it is narrowest", False),
]


def read_ply(path):
    """Vertices (n×3) and triangles (m×3) of a binary little-endian PLY as sdflow writes it."""
    with open(path, "rb") as f:
        vertices = faces = properties = 0
        current = None
        while True:
            words = f.readline().strip().split()
            if words[:2] == [b"element", b"vertex"]:
                vertices, current = int(words[2]), "vertex"
            elif words[:2] == [b"element", b"face"]:
                faces, current = int(words[2]), "face"
            elif words[:1] == [b"property"] and current == "vertex":
                properties += 1
            elif words == [b"end_header"]:
                break
        V = np.frombuffer(f.read(8 * properties * vertices), dtype="<f8").reshape(vertices, properties)[:, :3]
        F = np.frombuffer(f.read(13 * faces), dtype=np.dtype([("n", "u1"), ("i", "<i4", 3)]))["i"]
    return V.copy(), F.astype(np.int64)


def boundary_loops(F):
    """The number of boundary loops (each boundary vertex of a manifold mesh has one outgoing boundary halfedge)."""
    a, b = exact.boundary_halfedges(F)
    following = dict(zip(a.tolist(), b.tolist()))
    loops, seen = 0, set()
    for start in following:
        if start in seen:
            continue
        loops += 1
        v = start
        while v not in seen:
            seen.add(v)
            v = following[v]
    return loops


def rim_edges(V, F, ell):
    """The shortest and longest contact-line edge, in units of ℓ."""
    a, b = exact.boundary_halfedges(F)
    lengths = np.linalg.norm(V[a] - V[b], axis=1) / ell
    return f"{lengths.min():.3g}–{lengths.max():.3g}"


def measure(run, relaxes):
    metrics_path = os.path.join(run, "metrics.csv")
    log_path = os.path.join(run, "events.log")
    if not os.path.exists(metrics_path) or not os.path.exists(log_path):
        return "not run"
    with open(log_path) as f:
        if not re.search(r": (finished at|stopped:|interrupted:) ", f.read()):
            return "not finished"
    with open(metrics_path, newline="") as f:
        rows = list(csv.DictReader(f))
    with open(os.path.join(run, "run.toml"), "rb") as f:
        parameters = tomllib.load(f)
    with open(os.path.join(run, "events.log")) as f:
        log = f.read()
    first, last = rows[0], rows[-1]
    stopped = re.search(r": stopped: (.*)", log)
    snapshots = sorted(glob.glob(os.path.join(run, "snapshots", "step_*.ply")))
    V0, F0 = read_ply(snapshots[0])
    V1, F1 = read_ply(snapshots[-1])
    z0 = parameters["substrate"]["z"]
    cell = (f"{'stopped (exit 3: ' + stopped.group(1).rstrip() + ') after' if stopped else 'finished:'} "
            f"{last['step']} steps to t = {float(last['time']):.4g}, {first['vertices']} → {last['vertices']} vertices; "
            f"islands {first['components']} → {last['components']}, contact lines {boundary_loops(F0)} → {boundary_loops(F1)}")
    changes = []
    for before, after in zip(rows, rows[1:]):
        kinds = [k for k in after["event"].split("+") if k in ("touchdown", "contact")]
        if kinds or after["components"] != before["components"]:
            changes.append(f"{'+'.join(kinds) or 'change'} at t = {float(after['time']):.4g} "
                           f"(islands {before['components']} → {after['components']})")
    cell += "; " + ("; ".join(changes) if changes else "no topology change")
    volume0 = float(first["volume"]) + float(first["debris_volume"] or 0)
    volume1 = float(last["volume"]) + float(last["debris_volume"] or 0)
    a, _ = exact.boundary_halfedges(F1)
    ell = parameters["retriangulation"]["edge_length"]
    cell += (f"; volume {volume1 / volume0 - 1:+.1e} (relative); the contact line at most "
             f"{np.abs(V1[a, 2] - z0).max():.1e} off the plane, its edges {rim_edges(V0, F0, ell)} of ℓ at the start, "
             f"{rim_edges(V1, F1, ell)} at the end")
    if relaxes and not stopped:
        theta = parameters["substrate"]["contact_angle"]
        g = parameters["energy"]["g"] if parameters["energy"]["kind"] == "ellipsoidal" else None
        height, base = exact_shape_of(V1, F1, z0, float(last["volume"]), theta, g)
        cell += (f"; height {height[0]:.5f} against {height[1]:.5f} ({100 * (height[0] / height[1] - 1):+.2f}%), "
                 f"base radius {base[0]:.5f} against {base[1]:.5f} ({100 * (base[0] / base[1] - 1):+.2f}%)")
        if g is not None:
            cell += f", their ratio {height[0] / base[0]:.6f} against {height[1] / base[1]:.6f}"
    return cell


def exact_shape_of(V, F, z0, volume, theta, g):
    exact_height, exact_base = exact.exact_shape(volume, theta, g)
    return (float(V[:, 2].max() - z0), exact_height), (exact.base_radius(V, F), exact_base)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", default=os.path.join(HERE, "..", "runs"))
    parser.add_argument("--readme", default=os.path.join(HERE, "..", "README.md"))
    args = parser.parse_args()
    lines = ["| scenario | what it is | measured |", "|---|---|---|"]
    for name, what, relaxes in SAMPLES:
        lines.append(f"| `{name}` | {what} | {measure(os.path.join(args.runs, name), relaxes)} |")
    with open(args.readme) as f:
        text = f.read()
    begin, end = "<!-- substrate -->\n", "<!-- end of substrate -->"
    if begin not in text or end not in text:
        sys.exit(f"readme-substrate: {args.readme} lacks the markers {begin.strip()} and {end}")
    head, rest = text.split(begin, 1)
    _, tail = rest.split(end, 1)
    tmp = args.readme + ".tmp"
    with open(tmp, "w") as f:
        f.write(head + begin + "\n".join(lines) + "\n" + end + tail)
    os.replace(tmp, args.readme)
    print("\n".join(lines))


if __name__ == "__main__":
    main()
