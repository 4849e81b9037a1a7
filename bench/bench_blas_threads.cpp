//! Where a second BLAS thread starts to pay (solve/blas_threads.h): CHOLMOD's numeric factorisation
//! and whole reuse-policy steps on geodesic spheres, with the BLAS on 1 thread and on all hardware
//! threads. `cpu_per_wall` is the process's CPU time over the wall time: near 2 with a spinning
//! second thread that gains nothing.
//!   bench_blas_threads --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//! Quiet machine only: the 2-thread rows need both cores.

#include "flow_meshes.h"

#include "sdflow/flow/scheme.h"
#include "sdflow/solve/blas_threads.h"
#include "sdflow/solve/solver.h"

#include <benchmark/benchmark.h>

#include <Eigen/CholmodSupport>

#include <sys/resource.h>

#include <chrono>
#include <map>
#include <utility>
#include <thread>

namespace {

using sdflow::Mesh;

constexpr double perturbation = 0.05;
constexpr double tau = 1e-4;
constexpr double beta = 0.5;

const Mesh& sphere(int vertices)
{
  static std::map<int, Mesh> cache;
  auto it = cache.find(vertices);
  if (it == cache.end()) {
    const int k = static_cast<int>(std::lround(std::sqrt((vertices - 2) / 10.0)));
    it = cache.emplace(vertices, sdflow::bench::geodesic_sphere(k, perturbation)).first;
  }
  return it->second;
}

//! The process's user + system CPU seconds so far (all threads).
double process_cpu_seconds()
{
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * t.tv_usec; };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

//! Thread count of a row: 1, or 0 for all hardware threads.
int threads_of(const benchmark::State& state)
{
  return state.range(1) == 1 ? 1 : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

void Factorise(benchmark::State& state)
{
  const Mesh& mesh = sphere(static_cast<int>(state.range(0)));
  const auto op = sdflow::flow_operators(mesh);
  const sdflow::SparseMatrix a = sdflow::flow_matrix({op.laplacian, op.areas, op.held, tau * beta});
  Eigen::CholmodSupernodalLLT<sdflow::SparseMatrix, Eigen::Lower> llt;
  llt.analyzePattern(a);
  double cpu = 0, wall = 0;
  for (auto _ : state) {
    sdflow::set_factorisation_threads(threads_of(state));
    const double cpu_start = process_cpu_seconds();
    const auto start = std::chrono::steady_clock::now();
    llt.factorize(a);
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    cpu += process_cpu_seconds() - cpu_start;
  }
  sdflow::set_factorisation_threads(1);
  state.counters["threads"] = threads_of(state);
  state.counters["cpu_per_wall"] = cpu / wall;
}

//! Steps as the driver takes them (reuse policy: one factorisation, then preconditioned CG).
void Steps(benchmark::State& state)
{
  constexpr int steps = 10;
  const int threads = threads_of(state);
  // The policy's crossover moved so that this row's factorisations use `threads` threads.
  const sdflow::SolverOptions options{.blas = {.single_thread_below = threads == 1 ? 1L << 40 : 0}};
  double cpu = 0, wall = 0;
  for (auto _ : state) {
    state.PauseTiming();
    Mesh mesh = sphere(static_cast<int>(state.range(0)));
    const sdflow::CotangentCache cache(mesh);
    sdflow::FlowSolver solver(options);
    Eigen::VectorXd w, earlier_w;
    state.ResumeTiming();
    const double cpu_start = process_cpu_seconds();
    const auto start = std::chrono::steady_clock::now();
    for (int s = 0; s < steps; ++s) {
      const auto op = sdflow::flow_operators(mesh, {}, &cache);
      auto step = sdflow::solve_step(mesh, op, tau, beta, solver, sdflow::warm_starts(w, earlier_w));
      sdflow::set_vertex_positions(mesh, step.positions);
      earlier_w = std::exchange(w, std::move(step.w));
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    cpu += process_cpu_seconds() - cpu_start;
    wall += seconds;
    state.SetIterationTime(seconds / steps);
  }
  state.counters["threads"] = threads;
  state.counters["cpu_per_wall"] = cpu / wall;
}

} // namespace

BENCHMARK(Factorise)
    ->ArgsProduct({{25'000, 100'000, 400'000, 1'600'000}, {1, 0}})
    ->ArgNames({"vertices", "threads"})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(Steps)
    ->ArgsProduct({{25'000, 100'000, 400'000}, {1, 0}})
    ->ArgNames({"vertices", "threads"})
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
