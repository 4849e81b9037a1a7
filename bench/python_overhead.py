#!/usr/bin/env python3
"""Overhead of the Python module against the C++ API: the same flow (a torus of ~10k vertices,
100 steps, sdflow.Flow's defaults: adaptive τ, cotangent H, re-triangulation on) stepped

  C++     by SurfaceDiffusion's own loop (`while (...) flow.step();`, sdflow._sdflow._cpp_flow_seconds:
          the C++ API in this process, from the same arrays and parameters, no Python between steps);
  Python  by sdflow.Flow(V, F) and 100 calls of flow.step(), and by flow.advance(steps=100);
  Python+ as Python, reading flow.metrics after every step (what a notebook plotting the run does).

Runs alternate; medians of --runs runs each. Both ends must reach the same last metrics row
(the same computation), which the script checks.

    OPENBLAS_NUM_THREADS=1 PYTHONPATH=build/release/python python3 bench/python_overhead.py [--vertices 10000] [--steps 100] [--runs 5]\n\nOne BLAS thread makes runs repeatable on a shared machine (both ends use the same setting).
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
    parser.add_argument("--verbose", action="store_true", help="every run's time")
    args = parser.parse_args()

    V, F = sdflow.shape("torus", major=3, minor=1.5, vertices=args.vertices)
    parameters = _parameters.read({})  # Flow's defaults, as sdflow.Flow(V, F) reads them
    variants = {
        "C++ API (SurfaceDiffusion loop)": lambda: _sdflow._cpp_flow_seconds(V, F, parameters, args.steps),
        "Python Flow.step() x N": lambda: python_steps(V, F, args.steps, False),
        "Python Flow.advance(steps=N)": lambda: python_advance(V, F, args.steps),
        "Python step() + metrics each step": lambda: python_steps(V, F, args.steps, True),
    }
    times = {name: ([], [], []) for name in variants}
    rows = set()
    variants[next(iter(variants))]()  # warm-up (page cache, allocator)
    for _ in range(args.runs):
        for name, run in variants.items():
            cpu = time.process_time()
            total, stepping, row = run()
            times[name][2].append(time.process_time() - cpu)
            times[name][0].append(total)
            times[name][1].append(stepping)
            rows.add(row.rstrip("\n"))
    if len(rows) != 1:
        raise SystemExit(f"the variants ended on different rows: {rows}")
    print(f"torus R=3 r=1.5, {len(V)} vertices, {args.steps} steps, {args.runs} runs each (medians); "
          f"last row: {rows.pop()}")
    base_total = statistics.median(times["C++ API (SurfaceDiffusion loop)"][0])
    base_steps = statistics.median(times["C++ API (SurfaceDiffusion loop)"][1])
    base_min = min(times["C++ API (SurfaceDiffusion loop)"][0])
    base_cpu = statistics.median(times["C++ API (SurfaceDiffusion loop)"][2])
    print("wall: construction + steps, the steps alone, the fastest run; cpu: process CPU time (all threads),")
    print("less sensitive than wall time to other processes on the machine")
    print(f"{'variant':36s} {'wall s':>7s} {'over':>7s} {'steps s':>7s} {'over':>7s} {'min s':>6s} {'over':>7s}"
          f" {'cpu s':>6s} {'over':>7s}")
    for name, (total, stepping, cpu) in times.items():
        t, s, m, c = statistics.median(total), statistics.median(stepping), min(total), statistics.median(cpu)
        print(f"{name:36s} {t:7.3f} {100 * (t / base_total - 1):+6.1f}% {s:7.3f} {100 * (s / base_steps - 1):+6.1f}%"
              f" {m:6.3f} {100 * (m / base_min - 1):+6.1f}% {c:6.3f} {100 * (c / base_cpu - 1):+6.1f}%")
    if args.verbose:
        for name, (total, _, cpu) in times.items():
            print(f"  {name}: wall " + " ".join(f"{x:.3f}" for x in total) + "; cpu " + " ".join(f"{x:.3f}" for x in cpu))


if __name__ == "__main__":
    main()
