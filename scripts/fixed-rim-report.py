#!/usr/bin/env python3
"""What a run with a fixed boundary did to its rim and its material volume (docs/method.md).

  scripts/fixed-rim-report.py RUN_DIR

Reads RUN_DIR/metrics.csv and the PLY snapshots in RUN_DIR/snapshots (as `sdflow run` writes them):
- the topology events (rows whose component count or genus differ from the row before);
- the material volume (metrics.csv's `volume`): its relative change over the run, the largest
  relative drift between two events (from the first row after one event), and the jump at each event;
- for every snapshot, whether its boundary loops are step 0's: the same number of loops, each the
  same cyclic sequence of bit-identical vertices, run in the same direction.
Prints a plain-text report; exit code 1 when a snapshot's rim differs from step 0's.
"""
import csv
import os
import struct
import sys


def read_ply(path):
    """Vertex coordinates (tuples of the exact doubles) and triangles of a binary PLY from sdflow."""
    with open(path, "rb") as f:
        header = []
        while True:
            line = f.readline().decode("ascii").strip()
            header.append(line)
            if line == "end_header":
                break
        if "format binary_little_endian 1.0" not in header:
            raise SystemExit(f"{path}: not a binary little-endian PLY")
        vertex_count = face_count = 0
        vertex_properties = []
        element = None
        for line in header:
            words = line.split()
            if words[:1] == ["element"]:
                element = words[1]
                if element == "vertex":
                    vertex_count = int(words[2])
                elif element == "face":
                    face_count = int(words[2])
            elif words[:1] == ["property"] and element == "vertex":
                if words[1] != "double":
                    raise SystemExit(f"{path}: vertex property {words[2]} is {words[1]}, not double")
                vertex_properties.append(words[2])
        stride = 8 * len(vertex_properties)
        data = f.read(vertex_count * stride)
        points = [row[:3] for row in struct.iter_unpack("<" + "d" * len(vertex_properties), data)]
        faces = []
        for _ in range(face_count):
            (n,) = struct.unpack("<B", f.read(1))
            faces.append(struct.unpack("<" + "i" * n, f.read(4 * n)))
    return points, faces


def rim_loops(points, faces):
    """Boundary loops as lists of vertex coordinates, each in the direction of its faces' edges."""
    directed = set()
    for face in faces:
        for i in range(len(face)):
            directed.add((face[i], face[(i + 1) % len(face)]))
    following = {a: b for (a, b) in directed if (b, a) not in directed}
    loops, seen = [], set()
    for start in following:
        if start in seen:
            continue
        loop, v = [], start
        while v not in seen:
            seen.add(v)
            loop.append(points[v])
            v = following[v]
        loops.append(loop)
    return loops


def same_loops(before, after):
    """Each loop of `before` is a loop of `after`: the same cyclic sequence, the same direction."""
    if len(before) != len(after):
        return False
    for loop in before:
        found = False
        for other in after:
            if len(other) != len(loop) or loop[0] not in other:
                continue
            k = other.index(loop[0])
            if all(loop[i] == other[(k + i) % len(other)] for i in range(len(loop))):
                found = True
                break
        if not found:
            return False
    return True


def main():
    if len(sys.argv) != 2 or sys.argv[1] in ("-h", "--help"):
        print(__doc__.strip().split("\n\n")[1].strip())
        sys.exit(0 if len(sys.argv) == 2 else 2)
    run = sys.argv[1]
    with open(os.path.join(run, "metrics.csv")) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise SystemExit(f"{run}/metrics.csv has no rows")
    volume = lambda row: float(row["volume"])
    print(f"run {run}: steps 0-{rows[-1]['step']}, t = 0-{float(rows[-1]['time']):.6g}")
    events = [i for i in range(1, len(rows))
              if (rows[i]["components"], rows[i]["genus"]) != (rows[i - 1]["components"], rows[i - 1]["genus"])]
    print("events (step, t, components, genus, material volume before -> after, jump relative):")
    for i in events:
        before, after = volume(rows[i - 1]), volume(rows[i])
        print(f"  {rows[i]['step']:>6} t={float(rows[i]['time']):.6g} {rows[i - 1]['components']}->{rows[i]['components']} "
              f"genus {rows[i - 1]['genus']}->{rows[i]['genus']} {before:.9g} -> {after:.9g} ({(after - before) / before:+.2e})")
    start, end = volume(rows[0]), volume(rows[-1])
    print(f"material volume {start:.9g} -> {end:.9g}: {(end - start) / start:+.3e} over the run")
    bounds = [0] + events + [len(rows)]
    print("drift between events (from the row of one event to the row before the next):")
    for a, b in zip(bounds[:-1], bounds[1:]):
        segment = [volume(r) for r in rows[a:b]]
        drift = max(abs(v - segment[0]) for v in segment) / abs(segment[0])
        print(f"  steps {rows[a]['step']}-{rows[b - 1]['step']} (t = {float(rows[a]['time']):.6g}-{float(rows[b - 1]['time']):.6g}): "
              f"largest |V - V_start| / V_start = {drift:.2e}, end {(segment[-1] - segment[0]) / segment[0]:+.2e}")
    snapshots = sorted(f for f in os.listdir(os.path.join(run, "snapshots")) if f.endswith(".ply"))
    if not snapshots:
        return
    reference = rim_loops(*read_ply(os.path.join(run, "snapshots", snapshots[0])))
    print(f"rim of {snapshots[0]}: {len(reference)} loops, {sum(map(len, reference))} vertices")
    differing = []
    for name in snapshots[1:]:
        loops = rim_loops(*read_ply(os.path.join(run, "snapshots", name)))
        if not same_loops(reference, loops):
            differing.append(f"{name} ({len(loops)} loops, {sum(map(len, loops))} vertices)")
    print(f"rims bit-identical to {snapshots[0]} in {len(snapshots) - 1 - len(differing)} of {len(snapshots) - 1} "
          f"later snapshots" + ("; differing: " + ", ".join(differing) if differing else ""))
    sys.exit(1 if differing else 0)


if __name__ == "__main__":
    main()
