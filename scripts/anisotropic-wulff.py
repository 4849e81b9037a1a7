#!/usr/bin/env python3
"""Issue 35's targets for the anisotropic flow, measured with the command line.

A sphere of radius 1 (`sdflow shape sphere --vertices N`) flows under γ = √(nᵀ diag(g) n) without
re-triangulation and with its volume conserved (`--conserve-volume`) until END_TIME; its Wulff
shape is the ellipsoid of semi-axes ∝ √g of the sphere's volume. For each g and resolution the
table gives the semi-axes of the ellipsoid fitted to the last surface against the Wulff shape's
(largest relative error), the volume drift over the run, the steps in which ∫ γ dA (metrics.csv's
`energy`) increased by more than 10⁻¹² relative and the largest such increase, and the same two
figures and the drift for the run without the volume restoration, and the steps it rose and the
semi-axes error with the restoration and the volume-gradient mass (`--mass volume_gradient`, the
anisotropic samples' setting).
The cost of a step is bench/anisotropic_step_cost.sh's.

    scripts/anisotropic-wulff.py [--sdflow build/release/cli/sdflow] [--out runs/wulff]
                                 [--vertices 640,2500,10000] [--end-time 2]
"""
import argparse
import array
import csv
import math
import os
import subprocess
import sys


def read_ply_vertices(path):
    """x, y, z of a binary little-endian PLY whose vertex properties are all doubles (sdflow's)."""
    with open(path, "rb") as f:
        count, properties, line = 0, 0, b""
        in_vertex = False
        while line != b"end_header":
            line = f.readline().strip()
            words = line.split()
            if words[:2] == [b"element", b"vertex"]:
                count, in_vertex = int(words[2]), True
            elif words[:1] == [b"element"]:
                in_vertex = False
            elif words[:1] == [b"property"] and in_vertex:
                if words[1] != b"double":
                    sys.exit(f"{path}: vertex property {words[-1].decode()} is not a double")
                properties += 1
        data = array.array("d")
        data.frombytes(f.read(8 * properties * count))
    if sys.byteorder != "little":
        data.byteswap()
    return [data[i * properties:i * properties + 3] for i in range(count)]


def solve3(a, b):
    """x with a x = b for a 3×3 matrix (Cramer's rule; a is the normal matrix of a fit, well conditioned)."""
    det = lambda m: (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                     + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]))
    d = det(a)
    return [det([[b[r] if c == k else a[r][c] for c in range(3)] for r in range(3)]) / d for k in range(3)]


def fitted_semi_axes(points):
    """The axis-aligned ellipsoid x²/a² + y²/b² + z²/c² = 1 through the points about their centroid,
    by least squares (normal equations in 1/a², 1/b², 1/c²)."""
    centroid = [sum(p[k] for p in points) / len(points) for k in range(3)]
    squares = [[(p[k] - centroid[k]) ** 2 for k in range(3)] for p in points]
    normal = [[sum(s[i] * s[j] for s in squares) for j in range(3)] for i in range(3)]
    inverse_squares = solve3(normal, [sum(s[i] for s in squares) for i in range(3)])
    return [1 / math.sqrt(v) for v in inverse_squares]


def rows_of(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def run(sdflow, *arguments):
    subprocess.run([sdflow, *map(str, arguments)], check=True, stdout=subprocess.DEVNULL)


def sphere(sdflow, out, vertices):
    path = os.path.join(out, f"sphere_{vertices}.ply")
    if not os.path.exists(path):
        run(sdflow, "shape", "sphere", "--vertices", vertices, "-o", path)
    return path


def energy_increases(metrics):
    """The steps whose ∫ γ dA exceeds the previous step's by more than round-off, and the largest rise."""
    energies = [float(r["energy"]) for r in metrics]
    rises = [b / a - 1 for a, b in zip(energies, energies[1:]) if b > a * (1 + 1e-12)]
    return len(rises), max(rises, default=0.0)


def wulff_run(sdflow, out, mesh, g, end_time, conserve, mass="voronoi"):
    name = os.path.join(out, f"wulff_{'-'.join(map(str, g))}_{os.path.basename(mesh)[:-4]}"
                             f"{'' if conserve else '_free'}{'' if mass == 'voronoi' else '_' + mass}")
    if not os.path.exists(os.path.join(name, "metrics.csv")):
        run(sdflow, "run", "--input", mesh, "--out", name, "--end-time", end_time, "--no-retriangulate",
            "--conserve-volume" if conserve else "--no-conserve-volume", "--energy", "ellipsoidal",
            "--energy-g", ",".join(map(str, g)), "--mass", mass, "--snapshot-every", 0, "--quiet")
    return name, rows_of(os.path.join(name, "metrics.csv"))


def axes_error(name, g, volume):
    """The largest relative error of the semi-axes fitted to the run's last surface against the Wulff shape's."""
    last = sorted(f for f in os.listdir(os.path.join(name, "snapshots")) if f.endswith(".ply"))[-1]
    axes = fitted_semi_axes(read_ply_vertices(os.path.join(name, "snapshots", last)))
    root_g = [math.sqrt(v) for v in g]
    scale = (volume / (4 * math.pi / 3 * math.prod(root_g))) ** (1 / 3)
    return max(abs(a / (scale * w) - 1) for a, w in zip(axes, root_g))


def wulff_row(sdflow, out, mesh, g, end_time):
    name, metrics = wulff_run(sdflow, out, mesh, g, end_time, True)
    _, free = wulff_run(sdflow, out, mesh, g, end_time, False)
    gradient_name, gradient = wulff_run(sdflow, out, mesh, g, end_time, True, "volume_gradient")
    volume = float(metrics[0]["volume"])
    drift = lambda rows: abs(float(rows[-1]["volume"]) / float(rows[0]["volume"]) - 1)
    return {"g": g, "vertices": int(metrics[0]["vertices"]), "steps": int(metrics[-1]["step"]),
            "axes_error": axes_error(name, g, volume), "drift": drift(metrics),
            "increases": energy_increases(metrics), "free_increases": energy_increases(free),
            "free_drift": drift(free), "gradient_increases": energy_increases(gradient),
            "gradient_axes_error": axes_error(gradient_name, g, volume), "gradient_drift": drift(gradient),
            "energy_drop": 1 - float(metrics[-1]["energy"]) / float(metrics[0]["energy"])}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sdflow", default="build/release/cli/sdflow")
    parser.add_argument("--out", default="runs/wulff")
    parser.add_argument("--vertices", default="640,2500,10000")
    parser.add_argument("--end-time", type=float, default=2.0)
    a = parser.parse_args()
    os.makedirs(a.out, exist_ok=True)
    resolutions = [int(v) for v in a.vertices.split(",")]
    rows = [wulff_row(a.sdflow, a.out, sphere(a.sdflow, a.out, n), g, a.end_time)
            for g in ((1, 1, 4), (1, 2, 3)) for n in resolutions]
    print("| g | vertices | steps | semi-axes error | volume drift | ∫γ dA: decrease over the run | steps it rose "
          "(largest rise) | without restoration: steps it rose; volume drift | volume-gradient mass: steps it rose; "
          "semi-axes error; volume drift |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| ({', '.join(map(str, r['g']))}) | {r['vertices']} | {r['steps']} | {100 * r['axes_error']:.3f}% | "
              f"{r['drift']:.1e} | {100 * r['energy_drop']:.2f}% | {r['increases'][0]} ({r['increases'][1]:.1e}) | "
              f"{r['free_increases'][0]}; {r['free_drift']:.1e} | {r['gradient_increases'][0]}; "
              f"{100 * r['gradient_axes_error']:.3f}%; {r['gradient_drift']:.1e} |")


if __name__ == "__main__":
    main()
