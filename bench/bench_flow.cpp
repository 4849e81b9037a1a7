//! The flow step's cost on geodesic spheres of 10k, 100k and 400k vertices (docs/design.md §2):
//! operators, assembly, CHOLMOD factorisation and solve, and a full step amortised over a run.
//! FactorApplication and StaleFactorCg compare CHOLMOD's double factor with its single-precision
//! copy (solve/single_precision_factor.h): one application, and CG with a stale factor.
//!   bench_flow --benchmark_filter=Step --benchmark_repetitions=3
//! PaperQrStep is the paper's solver on the same spheres (slow: minutes at 10k vertices).
//! Step benchmarks report times per step (`factorisations` and `cg_iterations` per run); the others
//! say what their time covers.

#include "flow_meshes.h"

#include "sdflow/solve/blas_threads.h"
#include "sdflow/solve/carried_ordering.h"
#include "sdflow/flow/scheme.h"
#include "sdflow/solve/single_precision_factor.h"
#include "sdflow/solve/supernodal_cholesky.h"
#include "sdflow/solve/solver.h"
#include "sdflow/geometry/laplacian.h"
#include "sdflow/remesh/local_remesh.h"
#include "sdflow/remesh/remesh.h"
#include "sdflow/spatial/nearest_points.h"

#include <benchmark/benchmark.h>

#include <Eigen/CholmodSupport>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseQR>

#include <fmt/format.h>

#include <chrono>
#include <map>
#include <stdexcept>
#include <utility>

namespace {

using sdflow::Mesh;

constexpr double perturbation = 0.05; // P2 amplitude: the surface evolves, as in a real run
constexpr double tau = 1e-4;
constexpr double beta = 0.5;

//! k with 10k² + 2 vertices ≈ the requested count.
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

void Operators(benchmark::State& state)
{
  const Mesh& mesh = sphere(static_cast<int>(state.range(0)));
  for (auto _ : state)
    benchmark::DoNotOptimize(sdflow::flow_operators(mesh));
  state.counters["vertices"] = static_cast<double>(mesh.n_vertices());
}

//! The operators as the driver computes them, with the pattern of L kept between steps.
void OperatorsCached(benchmark::State& state)
{
  const Mesh& mesh = sphere(static_cast<int>(state.range(0)));
  const sdflow::CotangentCache cache(mesh);
  for (auto _ : state)
    benchmark::DoNotOptimize(sdflow::flow_operators(mesh, {}, &cache));
}

void Assembly(benchmark::State& state)
{
  const Mesh& mesh = sphere(static_cast<int>(state.range(0)));
  const auto op = sdflow::flow_operators(mesh);
  const sdflow::FlowSystem system{op.laplacian, op.areas, op.held, tau * beta};
  for (auto _ : state)
    benchmark::DoNotOptimize(sdflow::flow_matrix(system));
}

//! The step's assembled matrix M + τβ L M⁻¹ L on the sphere of about `vertices` vertices.
sdflow::SparseMatrix step_matrix(int vertices)
{
  const auto op = sdflow::flow_operators(sphere(vertices));
  return sdflow::flow_matrix({op.laplacian, op.areas, op.held, tau * beta});
}

void CholmodFactorise(benchmark::State& state)
{
  const sdflow::SparseMatrix a = step_matrix(static_cast<int>(state.range(0)));
  Eigen::CholmodSupernodalLLT<sdflow::SparseMatrix, Eigen::Lower> llt;
  llt.analyzePattern(a);
  for (auto _ : state)
    llt.factorize(a);
  state.counters["factor_nnz"] = llt.cholmod().lnz;
  state.counters["factor_gflop"] = llt.cholmod().fl * 1e-9;
  // CHOLMOD tries AMD and, when its fill is high, METIS and nested dissection (2 = AMD, 3 = METIS,
  // 4 = NESDIS), keeping the best.
  state.counters["ordering"] = llt.cholmod().method[llt.cholmod().selected].ordering;
}

//! The symbolic analysis alone, by ordering: 0 = CHOLMOD's default (AMD, then METIS and nested
//! dissection when AMD's fill is high), 1 = AMD only, 2 = METIS only. Counters: the factor's size and
//! the flops of one numeric factorisation with that ordering.
void CholmodAnalyse(benchmark::State& state)
{
  const sdflow::SparseMatrix a = step_matrix(static_cast<int>(state.range(0)));
  Eigen::CholmodSupernodalLLT<sdflow::SparseMatrix, Eigen::Lower> llt;
  if (state.range(1) != 0) {
    llt.cholmod().nmethods = 1;
    llt.cholmod().method[0].ordering = state.range(1) == 1 ? CHOLMOD_AMD : CHOLMOD_METIS;
  }
  for (auto _ : state)
    llt.analyzePattern(a);
  state.counters["factor_nnz"] = llt.cholmod().lnz;
  state.counters["factor_gflop"] = llt.cholmod().fl * 1e-9;
}

//! `mesh` with the faces of its cap z > 1 - 2 `fraction` (about that fraction of the area of the unit
//! sphere) remeshed locally at 0.7 times the mean edge length.
Mesh remeshed_cap(const Mesh& mesh, double fraction)
{
  std::vector<int> faces;
  double length = 0;
  for (const auto e : mesh.edges())
    length += mesh.calc_edge_length(e);
  length /= static_cast<double>(mesh.n_edges());
  for (const auto f : mesh.faces())
    if (mesh.calc_face_centroid(f)[2] > 1 - 2 * fraction)
      faces.push_back(f.idx());
  return sdflow::remesh_locally(mesh, faces, {}, {.edge_length = 0.7 * length}).mesh;
}

//! The analysis after a re-triangulation: the third argument 0 remeshes the whole sphere
//! isotropically (every vertex new), 1 a cap of 5% of its area (remesh_locally);
//! the second argument 0 orders afresh (CHOLMOD's default), 1 carries the old analysis's ordering to the new
//! vertices by nearest old vertex (the nearest-point search included in the time). Counter
//! `fill_ratio`: the factor's non-zeros relative to the fresh ordering's.
void CarriedOrdering(benchmark::State& state)
{
  const int vertices = static_cast<int>(state.range(0));
  const Mesh& before = sphere(vertices);
  sdflow::SupernodalCholesky old_analysis;
  old_analysis.analyse(step_matrix(vertices));
  const Mesh after = state.range(2) == 0 ? sdflow::isotropic_remesh(before, {.iterations = 3}).mesh
                                         : remeshed_cap(before, 0.05);
  const auto op = sdflow::flow_operators(after);
  const sdflow::SparseMatrix a = sdflow::flow_matrix({op.laplacian, op.areas, op.held, tau * beta});
  sdflow::SupernodalCholesky fresh;
  fresh.analyse(a);
  const sdflow::VertexVectors old_points = sdflow::vertex_positions(before);
  const sdflow::VertexVectors new_points = sdflow::vertex_positions(after);
  sdflow::SupernodalCholesky analysis;
  for (auto _ : state) {
    if (state.range(1) == 0) {
      analysis.analyse(a);
    } else {
      const std::vector<int> nearest = sdflow::nearest_points(old_points, new_points);
      analysis.analyse(a, sdflow::carried_ordering(old_analysis.elimination_tree(), nearest, op.laplacian));
    }
  }
  state.counters["vertices"] = static_cast<double>(after.n_vertices());
  state.counters["fill_ratio"] = analysis.factor_nonzeros() / fresh.factor_nonzeros();
  state.counters["flop_ratio"] = analysis.factorisation_flops() / fresh.factorisation_flops();
}

void CholmodSolve(benchmark::State& state)
{
  const Mesh& mesh = sphere(static_cast<int>(state.range(0)));
  const auto op = sdflow::flow_operators(mesh);
  const sdflow::FlowSystem system{op.laplacian, op.areas, op.held, tau * beta};
  Eigen::CholmodSupernodalLLT<sdflow::SparseMatrix, Eigen::Lower> llt(sdflow::flow_matrix(system));
  for (auto _ : state)
    benchmark::DoNotOptimize(Eigen::VectorXd(llt.solve(op.rhs)));
}

//! The step matrix's supernodal factor as FlowSolver makes it (CHOLMOD's own choice of ordering).
sdflow::SupernodalCholesky factorised(const sdflow::SparseMatrix& a)
{
  sdflow::SupernodalCholesky cholesky;
  cholesky.analyse(a);
  if (!cholesky.factorise(a))
    throw std::runtime_error("the step matrix is not positive definite");
  return cholesky;
}

//! Bytes of the double factor's values, the part a triangular solve streams.
double factor_value_bytes(const cholmod_factor& factor) { return static_cast<double>(factor.xsize) * sizeof(double); }

//! One application of the step matrix's factor (a forward and a backward triangular solve):
//! variant 0 = CHOLMOD's double cholmod_solve, 1 = its single-precision copy (SinglePrecisionFactor).
//! Counters: the bytes each variant holds (factor_MB), bytes processed = the values read twice, and
//! the float solve's relative difference from the double one (float_error).
void FactorApplication(benchmark::State& state)
{
  const int vertices = static_cast<int>(state.range(0));
  const bool single = state.range(1) == 1;
  const sdflow::SparseMatrix a = step_matrix(vertices);
  const sdflow::SupernodalCholesky cholesky = factorised(a);
  const sdflow::SinglePrecisionFactor single_factor(cholesky.factor());
  sdflow::set_factorisation_threads(1); // solves run on one thread, as FlowSolver runs them
  const auto op = sdflow::flow_operators(sphere(vertices));
  const cholmod_factor& factor = cholesky.factor();
  const double structure_bytes =
      static_cast<double>(3 * (factor.nsuper + 1) + factor.ssize + factor.n) * sizeof(int);
  const double value_bytes = single ? factor_value_bytes(factor) / 2 : factor_value_bytes(factor);
  for (auto _ : state) {
    if (single)
      benchmark::DoNotOptimize(single_factor.solve(op.rhs));
    else
      benchmark::DoNotOptimize(cholesky.solve(op.rhs));
  }
  const Eigen::VectorXd exact = cholesky.solve(op.rhs);
  state.counters["float_error"] = (single_factor.solve(op.rhs) - exact).norm() / exact.norm();
  state.counters["factor_MB"] =
      (single ? static_cast<double>(single_factor.bytes()) : value_bytes + structure_bytes) * 1e-6;
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * 2 * value_bytes));
  state.SetLabel(single ? "float" : "double cholmod_solve");
}

//! Conjugate gradients on a step's system of the flowing sphere, preconditioned by a stale factor,
//! from zero to FlowSolver's tolerance 1e-10 on the residual; time per CG solve.
//! range(1): 0 = CHOLMOD's double solve, 1 = its float copy (SinglePrecisionFactor).
//! range(2): the stale factor is 0 = the factor of the surface 10 steps earlier, 1 = the factor of
//! the same surface with τβ 10% larger. Counters: iterations, the final true relative residual.
void StaleFactorCg(benchmark::State& state)
{
  constexpr int stale_steps = 10;
  constexpr double tolerance = 1e-10;
  const int vertices = static_cast<int>(state.range(0));
  const bool single = state.range(1) == 1;
  const bool earlier_surface = state.range(2) == 0;
  Mesh mesh = sphere(vertices);
  const sdflow::CotangentCache cache(mesh);
  if (earlier_surface) {
    sdflow::FlowSolver solver;
    for (int s = 0; s < stale_steps; ++s) {
      const auto op = sdflow::flow_operators(mesh, {}, &cache);
      sdflow::set_vertex_positions(mesh, sdflow::solve_step(mesh, op, tau, beta, solver).positions);
    }
  }
  const auto op = sdflow::flow_operators(mesh, {}, &cache);
  const sdflow::SparseMatrix a = sdflow::flow_matrix({op.laplacian, op.areas, op.held, tau * beta});
  const auto stale_op = sdflow::flow_operators(sphere(vertices), {}, &cache);
  const sdflow::SupernodalCholesky cholesky = factorised(sdflow::flow_matrix(
      {stale_op.laplacian, stale_op.areas, stale_op.held, (earlier_surface ? 1.0 : 1.1) * tau * beta}));
  const sdflow::SinglePrecisionFactor single_factor(cholesky.factor());
  sdflow::set_factorisation_threads(1);
  const auto precondition = [&](const Eigen::VectorXd& r) {
    return single ? single_factor.solve(r) : cholesky.solve(r);
  };
  const Eigen::VectorXd& b = op.rhs;
  int iterations = 0;
  double residual = 0;
  for (auto _ : state) {
    Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size()), r = b, z = precondition(r), p = z;
    double rz = r.dot(z);
    for (iterations = 1; iterations <= 100; ++iterations) {
      const Eigen::VectorXd ap = a * p;
      const double alpha = rz / p.dot(ap);
      x += alpha * p;
      r -= alpha * ap;
      if (r.norm() <= tolerance * b.norm())
        break;
      z = precondition(r);
      const double rz_next = r.dot(z);
      p = z + (rz_next / rz) * p;
      rz = rz_next;
    }
    residual = (b - a * x).norm() / b.norm();
  }
  state.counters["cg_iterations"] = iterations;
  state.counters["relative_residual"] = residual;
  state.SetLabel(fmt::format("{}; factor of {}", single ? "float" : "double cholmod_solve",
                             earlier_surface ? "10 steps earlier" : "1.1 tau*beta"));
}

//! `steps` full steps (operators + solve + update) on a copy of the sphere, as the driver runs them
//! (kept pattern of L, one solver, warm-started solves); time per step.
void run_steps(benchmark::State& state, sdflow::FactorisationPolicy policy)
{
  const int steps = static_cast<int>(state.range(1));
  long factorisations = 0, iterations = 0;
  for (auto _ : state) {
    state.PauseTiming();
    Mesh mesh = sphere(static_cast<int>(state.range(0)));
    const sdflow::CotangentCache cache(mesh);
    sdflow::FlowSolver solver({.policy = policy});
    Eigen::VectorXd w, earlier_w;
    factorisations = iterations = 0;
    state.ResumeTiming();
    const auto start = std::chrono::steady_clock::now();
    for (int s = 0; s < steps; ++s) {
      const auto op = sdflow::flow_operators(mesh, {}, &cache);
      auto step = sdflow::solve_step(mesh, op, tau, beta, solver, sdflow::warm_starts(w, earlier_w));
      sdflow::set_vertex_positions(mesh, step.positions);
      earlier_w = std::exchange(w, std::move(step.w));
      factorisations += step.solve.factorised;
      iterations += step.solve.iterations;
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    state.SetIterationTime(seconds / steps);
  }
  state.counters["factorisations"] = static_cast<double>(factorisations);
  state.counters["cg_iterations"] = static_cast<double>(iterations);
}

void StepReuse(benchmark::State& state) { run_steps(state, sdflow::FactorisationPolicy::reuse); }

//! One step solved as the paper did: SuiteSparseQR on (I + τβΔ²) w = ΔH (operators included).
void PaperQrStep(benchmark::State& state)
{
  const Mesh& mesh = sphere(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    sdflow::FlowSolver solver({.kind = sdflow::SolverKind::qr});
    const auto op = sdflow::flow_operators(mesh);
    benchmark::DoNotOptimize(sdflow::solve_step(mesh, op, tau, beta, solver));
  }
}
void StepEveryStep(benchmark::State& state) { run_steps(state, sdflow::FactorisationPolicy::every_step); }

} // namespace

BENCHMARK(Operators)->Arg(10'000)->Arg(100'000)->Arg(400'000)->Unit(benchmark::kMillisecond);
BENCHMARK(OperatorsCached)->Arg(10'000)->Arg(100'000)->Arg(400'000)->Unit(benchmark::kMillisecond);
BENCHMARK(Assembly)->Arg(10'000)->Arg(100'000)->Arg(400'000)->Unit(benchmark::kMillisecond);
BENCHMARK(CholmodFactorise)->Arg(10'000)->Arg(100'000)->Arg(400'000)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK(CholmodAnalyse)->ArgsProduct({{10'000, 100'000, 400'000}, {0, 1, 2}})->Unit(benchmark::kMillisecond);
BENCHMARK(CarriedOrdering)->ArgsProduct({{10'000, 100'000, 400'000}, {0, 1}, {0, 1}})->Unit(benchmark::kMillisecond);
BENCHMARK(CholmodSolve)->Arg(10'000)->Arg(100'000)->Arg(400'000)->Unit(benchmark::kMillisecond);
BENCHMARK(FactorApplication)->ArgsProduct({{25'000, 100'000}, {0, 1}})->Unit(benchmark::kMillisecond);
BENCHMARK(StaleFactorCg)->ArgsProduct({{25'000, 100'000}, {0, 1}, {0, 1}})->Unit(benchmark::kMillisecond);
BENCHMARK(StepReuse)->Args({10'000, 100})->Args({100'000, 100})->Args({400'000, 30})
    ->UseManualTime()->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(StepEveryStep)->Args({10'000, 20})->Args({100'000, 5})->Args({400'000, 3})
    ->UseManualTime()->Iterations(1)->Unit(benchmark::kMillisecond);
//! The paper's implementation solved with Eigen's own SparseQR (COLAMD ordering): the solver the
//! paper's program used, as a historical reference (bench only; sdflow's `--solver qr` is SPQR).
void EigenSparseQrStep(benchmark::State& state)
{
  const Mesh& mesh = sphere(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    const auto op = sdflow::flow_operators(mesh);
    const Eigen::VectorXd inverse_areas = op.areas.cwiseInverse();
    const sdflow::SparseMatrix delta = inverse_areas.asDiagonal() * op.laplacian;
    sdflow::SparseMatrix a = delta * delta * (tau * beta);
    for (Eigen::Index i = 0; i < a.rows(); ++i)
      a.coeffRef(i, i) += 1.0;
    a.makeCompressed();
    Eigen::SparseQR<sdflow::SparseMatrix, Eigen::COLAMDOrdering<int>> qr(a);
    benchmark::DoNotOptimize(Eigen::VectorXd(qr.solve(Eigen::VectorXd(op.rhs.cwiseQuotient(op.areas)))));
  }
}

BENCHMARK(PaperQrStep)->Arg(2'500)->Arg(10'000)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(EigenSparseQrStep)->Arg(2'500)->Arg(10'000)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
