//! Side by side: sdflow against Surface Evolver (`evolver-nox`, method laplacian_mean_curvature,
//! explicit) carrying the l = 2 mode of a perturbed unit sphere to t = 0.05. Each reports the decay
//! rate it measured (exact: (l-1)l(l+1)(l+2)/2 = 12, docs/design.md §1), its relative error and its time,
//! so the two can be compared at equal accuracy; sdflow runs with the paper's eq. (9) H, with the
//! cotangent H, and with the cotangent H over volume-gradient areas (`mass = "volume_gradient"`, the
//! spatial discretisation Evolver's method uses), plain or Richardson-extrapolated (docs/flow.md).
//! `cpu_s` is the CPU time (the Evolver process's own for Evolver), meaningful when the machine is
//! shared; Time is wall-clock. The Evolver rows are skipped when `evolver-nox-d` is not installed
//! (scripts/install-deps.sh --bench).
//!   bench_flow_decay --benchmark_counters_tabular=true

#include "sdflow/flow/scheme.h"
#include "sdflow/flow/surface_diffusion.h"
#include "support/analytic_meshes.h"

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sys/resource.h>
#include <unistd.h>
#include <vector>

namespace {

using sdflow::Mesh;

constexpr double amplitude = 0.01;
constexpr double end_time = 0.05;
constexpr double exact_rate = 12.0;

Mesh perturbed_sphere(int level)
{
  Mesh mesh = sdflow::analytic::icosphere(level);
  for (auto v : mesh.vertices()) {
    const auto p = mesh.point(v);
    mesh.set_point(v, p * (1 + amplitude * 0.5 * (3 * p[2] * p[2] - 1)));
  }
  return mesh;
}

//! Least-squares fit |x| = a0 + a2 P2(z/|x|) over the vertices (unweighted, the same for both codes).
double p2_amplitude(const std::vector<Eigen::Vector3d>& points)
{
  double n = 0, sp = 0, spp = 0, sr = 0, srp = 0;
  for (const auto& x : points) {
    const double r = x.norm(), c = x.z() / r, p = 0.5 * (3 * c * c - 1);
    n += 1;
    sp += p;
    spp += p * p;
    sr += r;
    srp += r * p;
  }
  return (n * srp - sp * sr) / (n * spp - sp * sp);
}

std::vector<Eigen::Vector3d> points_of(const Mesh& mesh)
{
  std::vector<Eigen::Vector3d> points;
  for (auto v : mesh.vertices())
    points.push_back(sdflow::to_eigen(mesh.point(v)));
  return points;
}

//! CPU seconds (user + system) of this process, or of its finished children.
double cpu_seconds(int who)
{
  rusage usage{};
  getrusage(who, &usage);
  return usage.ru_utime.tv_sec + usage.ru_stime.tv_sec + 1e-6 * (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

void report(benchmark::State& state, double a0, double a1, double seconds, int vertices)
{
  const double rate = -std::log(a1 / a0) / end_time;
  state.SetIterationTime(seconds);
  state.counters["vertices"] = vertices;
  state.counters["rate"] = rate;
  state.counters["rate_error_pct"] = 100 * std::abs(rate - exact_rate) / exact_rate;
}

//! sdflow: `steps` semi-implicit steps of constant τ (β = 1/2) from t = 0 to t = 0.05, with H by
//! eq. (9) (third argument 0, the default), the cotangent H (1), or the cotangent H over
//! volume-gradient areas (2); the fourth argument 1 Richardson-extrapolates each step (3 solves).
void Sdflow(benchmark::State& state)
{
  const int level = static_cast<int>(state.range(0)), steps = static_cast<int>(state.range(1));
  const int variant = static_cast<int>(state.range(2));
  const bool extrapolate = state.range(3) == 1;
  const sdflow::SchemeOptions scheme{
      .curvature = {.method = variant == 0 ? sdflow::CurvatureMethod::normal_curvature_integral
                                           : sdflow::CurvatureMethod::cotangent},
      .mass = variant == 2 ? sdflow::VertexMass::volume_gradient : sdflow::VertexMass::voronoi,
      .extrapolate = extrapolate};
  const char* name = variant == 0 ? "eq. 9 H" : variant == 1 ? "cotangent H" : "cotangent H, volume-gradient M";
  state.SetLabel(fmt::format("{}{}", name, extrapolate ? ", extrapolated" : ""));
  const Mesh start = perturbed_sphere(level);
  for (auto _ : state) {
    const double cpu_begin = cpu_seconds(RUSAGE_SELF);
    const auto begin = std::chrono::steady_clock::now();
    sdflow::FlowOptions p;
    p.retriangulation.enabled = false;
    p.steps = steps;
    p.time_step.mode = sdflow::TimeStepMode::constant;
    p.time_step.tau = end_time / steps;
    p.scheme = scheme;
    sdflow::SurfaceDiffusion flow(start, p);
    while (!flow.finished())
      flow.step();
    const Mesh& mesh = flow.mesh();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    report(state, p2_amplitude(points_of(start)), p2_amplitude(points_of(mesh)), seconds,
           static_cast<int>(mesh.n_vertices()));
    state.counters["cpu_s"] = cpu_seconds(RUSAGE_SELF) - cpu_begin;
  }
}

//! Surface Evolver: explicit motion by the Laplacian of mean curvature with a fixed scale (time step)
//! of 1e-5 / 16^(level-2), below its stability limit (about 0.001 h⁴, Evolver's documentation).
void Evolver(benchmark::State& state)
{
  if (std::system("command -v evolver-nox-d > /dev/null 2>&1") != 0) {
    state.SkipWithError("evolver-nox-d not installed (scripts/install-deps.sh --bench)");
    return;
  }
  const int level = static_cast<int>(state.range(0));
  const double scale = 1e-5 / std::pow(16.0, level - 2);
  const long iterations = std::lround(end_time / scale);
  const Mesh start = perturbed_sphere(level);
  const auto dir = std::filesystem::temp_directory_path() / fmt::format("sdflow_evolver_{}", ::getpid());
  std::filesystem::create_directories(dir);
  {
    std::ofstream fe(dir / "sphere.fe");
    fe << "area_method_name \"null_area\"\nquantity lmc energy method laplacian_mean_curvature global\n\nvertices\n";
    for (auto v : start.vertices()) {
      const auto p = start.point(v);
      fe << fmt::format("{} {} {} {}\n", v.idx() + 1, p[0], p[1], p[2]);
    }
    fe << "\nedges\n";
    for (auto e : start.edges())
      fe << fmt::format("{} {} {}\n", e.idx() + 1, e.v0().idx() + 1, e.v1().idx() + 1);
    fe << "\nfaces\n";
    for (auto f : start.faces()) {
      fe << f.idx() + 1;
      for (auto h : f.halfedges())
        fe << ' ' << (h.edge().v0() == h.from() ? 1 : -1) * (h.edge().idx() + 1);
      fe << '\n';
    }
    fe << "\nbodies\n1"; // the method moves along the volume gradient: the surface must bound a body
    for (auto f : start.faces())
      fe << ' ' << f.idx() + 1;
    fe << '\n';
    std::ofstream commands(dir / "run.cmd");
    commands << fmt::format("quiet on\nm {}\ng {}\n", scale, iterations)
             << "foreach vertex vv do printf \"%.17g %.17g %.17g\\n\", vv.x, vv.y, vv.z >> \"final.txt\"\nq\n";
  }
  for (auto _ : state) {
    std::filesystem::remove(dir / "final.txt");
    const double cpu_begin = cpu_seconds(RUSAGE_CHILDREN);
    const auto begin = std::chrono::steady_clock::now();
    const int status = std::system(fmt::format("cd '{}' && evolver-nox-d -x -f run.cmd sphere.fe > evolver.log 2>&1",
                                               dir.string()).c_str());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    std::vector<Eigen::Vector3d> final;
    std::ifstream in(dir / "final.txt");
    for (Eigen::Vector3d x; in >> x.x() >> x.y() >> x.z();)
      final.push_back(x);
    if (status != 0 || final.size() != start.n_vertices()) {
      state.SkipWithError("Surface Evolver failed (see its log in the temporary folder)");
      return;
    }
    report(state, p2_amplitude(points_of(start)), p2_amplitude(final), seconds, static_cast<int>(final.size()));
    state.counters["cpu_s"] = cpu_seconds(RUSAGE_CHILDREN) - cpu_begin;
    state.counters["iterations"] = static_cast<double>(iterations);
  }
  std::filesystem::remove_all(dir);
}

} // namespace

//! Both H at levels 2..5 with the steps of the Evolver comparison, then the cotangent H with fewer
//! and more steps at levels 2 and 3 (is the time-step error or the mesh's the larger there?), then
//! the volume-gradient areas at levels 2..4 from 25 to 1600 steps, then extrapolated steps (3 to 96)
//! with eq. (9) and with the volume-gradient areas.
void sdflow_cases(benchmark::internal::Benchmark* b)
{
  for (int variant : {0, 1})
    for (int level = 2; level <= 5; ++level)
      b->Args({level, 50 << (level - 2), variant, 0});
  for (int steps : {6, 12, 25, 100, 200})
    b->Args({2, steps, 1, 0});
  for (int steps : {12, 25, 50, 200, 400})
    b->Args({3, steps, 1, 0});
  for (int level = 2; level <= 4; ++level)
    for (int steps = 25; steps <= 1600; steps *= 2)
      b->Args({level, steps, 2, 0});
  for (int variant : {0, 2})
    for (int level = 2; level <= 4; ++level)
      for (int steps = 3; steps <= 100; steps *= 2)
        b->Args({level, steps, variant, 1});
}

BENCHMARK(Sdflow)->Apply(sdflow_cases)->UseManualTime()->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(Evolver)->Arg(2)->Arg(3)->UseManualTime()->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
