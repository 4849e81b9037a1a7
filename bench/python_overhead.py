#!/usr/bin/env python3
"""Overhead of the Python module against the C++ API: the same flow (a torus of ~10k vertices,
100 steps, sdflow.Flow's defaults: adaptive τ, cotangent H, re-triangulation on) stepped

  C++     by SurfaceDiffusion's own loop (`while (...) flow.step();`, sdflow._sdflow._cpp_flow_seconds:
          the C++ API in this process, from the same arrays and parameters, no Python between steps);
  Python  by sdflow.Flow(V, F) and 100 calls of flow.step(), and by flow.advance(steps=100);
  Python+ as Python, reading flow.metrics after every step (what a notebook plotting the run does).

Runs alternate; medians of --runs runs each. Both ends must reach the same last metrics row
(the same computation), which the script checks.

    PYTHONPATH=build/release/python python3 bench/python_overhead.py [--vertices 10000] [--steps 100] [--runs 5]
"""

import argparse
import statistics
import time

import sdflow
from sdflow import _parameters, _sdflow


def python_steps(V, F, steps, read_metrics):
    start = time.perf_counter()
    flow = sdflow.Flow(V, F)
    constructed = time.perf_counter()
    for _ in range(steps):
        flow.step()
        if read_metrics:
            flow.metrics
    end = time.perf_counter()
    return end - start, end - constructed, flow.metrics_row


def python_advance(V, F, steps):
    start = time.perf_counter()
    flow = sdflow.Flow(V, F)
    constructed = time.perf_counter()
    flow.advance(steps=steps)
    end = time.perf_counter()
    return end - start, end - constructed, flow.metrics_row


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--vertices", type=int, default=10000)
    parser.add_argument("--steps", type=int, default=100)
    parser.add_argument("--runs", type=int, default=5)
    args = parser.parse_args()

    V, F = sdflow.shape("torus", major=3, minor=1.5, vertices=args.vertices)
    parameters = _parameters.read({})  # Flow's defaults, as sdflow.Flow(V, F) reads them
    variants = {
        "C++ API (SurfaceDiffusion loop)": lambda: _sdflow._cpp_flow_seconds(V, F, parameters, args.steps),
        "Python Flow.step() x N": lambda: python_steps(V, F, args.steps, False),
        "Python Flow.advance(steps=N)": lambda: python_advance(V, F, args.steps),
        "Python step() + metrics each step": lambda: python_steps(V, F, args.steps, True),
    }
    times = {name: ([], []) for name in variants}
    rows = set()
    variants[next(iter(variants))]()  # warm-up (page cache, allocator)
    for _ in range(args.runs):
        for name, run in variants.items():
            total, stepping, row = run()
            times[name][0].append(total)
            times[name][1].append(stepping)
            rows.add(row.rstrip("\n"))
    if len(rows) != 1:
        raise SystemExit(f"the variants ended on different rows: {rows}")
    print(f"torus R=3 r=1.5, {len(V)} vertices, {args.steps} steps, {args.runs} runs each (medians); "
          f"last row: {rows.pop()}")
    base_total = statistics.median(times["C++ API (SurfaceDiffusion loop)"][0])
    base_steps = statistics.median(times["C++ API (SurfaceDiffusion loop)"][1])
    print(f"{'variant':38s} {'total s':>9s} {'overhead':>9s} {'steps s':>9s} {'overhead':>9s}")
    for name, (total, stepping) in times.items():
        t, s = statistics.median(total), statistics.median(stepping)
        print(f"{name:38s} {t:9.3f} {100 * (t / base_total - 1):+8.2f}% {s:9.3f} {100 * (s / base_steps - 1):+8.2f}%")


if __name__ == "__main__":
    main()
