//! Meshing the paper's initial surfaces: the 100k-vertex torus of issue 4 (seconds, not minutes),
//! its two stages (marching tetrahedra, remeshing), and the paper-resolution union shapes.
//! Run: build/bench/bench_shapes --benchmark_repetitions=3 --benchmark_report_aggregates_only=true

#include "sdflow/remesh/remesh.h"
#include "sdflow/shapes/catalogue.h"
#include "sdflow/shapes/marching_tetrahedra.h"
#include "sdflow/shapes/mesher.h"

#include <benchmark/benchmark.h>

namespace {

void report(benchmark::State& state, const sdflow::MesherResult& r)
{
  state.counters["vertices"] = static_cast<double>(r.mesh.n_vertices());
  state.counters["min_angle_p05"] = r.min_angles.p05;
  state.counters["min_angle"] = r.min_angles.min;
}

//! The figure: `sdflow shape torus --vertices 100000`.
void torus_100k(benchmark::State& state)
{
  const auto torus = sdflow::torus_shape();
  for (auto _ : state) {
    auto r = sdflow::mesh_implicit_surface(torus, {.vertices = 100000});
    report(state, r);
    benchmark::DoNotOptimize(r);
  }
}
BENCHMARK(torus_100k)->Unit(benchmark::kSecond)->Iterations(1);

//! The first stage alone, at the grid the 100k torus uses.
void torus_marching(benchmark::State& state)
{
  const auto torus = sdflow::torus_shape();
  for (auto _ : state) {
    auto mesh = sdflow::marching_tetrahedra(torus, {.cell_size = 0.175});
    state.counters["vertices"] = static_cast<double>(mesh.n_vertices());
    benchmark::DoNotOptimize(mesh);
  }
}
BENCHMARK(torus_marching)->Unit(benchmark::kMillisecond)->Iterations(1);

//! Remeshing alone: a 100k-vertex torus mesh remeshed to ℓ (3 iterations, as in the paper's
//! pipeline), projecting analytically.
void torus_remesh_3_iterations(benchmark::State& state)
{
  const auto torus = sdflow::torus_shape();
  const sdflow::Mesh input = sdflow::mesh_implicit_surface(torus, {.edge_length = 0.0875, .iterations = 2}).mesh;
  const auto project = [&](const Eigen::Vector3d& p) { return sdflow::project_to_level_set(torus, p); };
  for (auto _ : state) {
    auto r = sdflow::isotropic_remesh(input, {.edge_length = 0.0875, .iterations = 3, .project = project});
    state.counters["vertices"] = static_cast<double>(r.mesh.n_vertices());
    benchmark::DoNotOptimize(r);
  }
}
BENCHMARK(torus_remesh_3_iterations)->Unit(benchmark::kSecond)->Iterations(1);

//! The sintering cluster at the paper's resolution (51311 vertices, §4.2).
void sintering_paper(benchmark::State& state)
{
  const auto cluster = sdflow::sintering_cluster_shape();
  for (auto _ : state) {
    auto r = sdflow::mesh_implicit_surface(cluster, {.vertices = 51311});
    report(state, r);
    benchmark::DoNotOptimize(r);
  }
}
BENCHMARK(sintering_paper)->Unit(benchmark::kSecond)->Iterations(1);

//! Three spheres on a plane at the paper's resolution (95657 vertices, §4.3).
void spheres_on_plane_paper(benchmark::State& state)
{
  const auto scene = sdflow::spheres_on_plane_shape();
  for (auto _ : state) {
    auto r = sdflow::mesh_implicit_surface(scene, {.vertices = 95657});
    report(state, r);
    benchmark::DoNotOptimize(r);
  }
}
BENCHMARK(spheres_on_plane_paper)->Unit(benchmark::kSecond)->Iterations(1);

} // namespace

BENCHMARK_MAIN();
