//! Surgery at a pinch-off: the local surgery (retri/local_surgery.h) against the whole-surface
//! pipeline (retri/pipeline.h) on the same self-intersecting dumbbell, its neck pinched through
//! the axis by a quarter of an edge (a run's steps move vertices by at most 5% of an edge, so the
//! hook finds crossings that shallow), at about 20k and 100k vertices (the local surgery at 150k
//! too). Wall and process CPU time (all threads).
#include "sdflow/geometry/measures.h"
#include "sdflow/retri/local_surgery.h"
#include "sdflow/retri/pipeline.h"
#include "sdflow/shapes/catalogue.h"
#include "sdflow/shapes/mesher.h"
#include "sdflow/spatial/intersect.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <map>

namespace {

using namespace sdflow;

//! The half-size paper dumbbell (end spheres of radius 3, neck radius 0.5) at about `vertices`
//! vertices, its neck drawn in by (0.5 + h/4)(1 - (x/0.3)²) over |x| < 0.3, h the mean edge
//! length: it crosses the axis by up to a quarter of an edge at x = 0.
const Mesh& pinched_dumbbell(int vertices)
{
  static std::map<int, Mesh> meshes;
  auto it = meshes.find(vertices);
  if (it != meshes.end())
    return it->second;
  Mesh mesh = mesh_implicit_surface(dumbbell_shape({.radius = 3, .separation = 9}), {.vertices = vertices}).mesh;
  const double depth = 0.5 + mean_edge_length(mesh) / 4;
  for (const auto v : mesh.vertices()) {
    const Eigen::Vector3d p = to_eigen(mesh.point(v));
    const double rho = std::hypot(p.y(), p.z()), u = p.x() / 0.3;
    if (std::abs(u) < 1 && rho > 0) {
      const double scale = (rho - depth * (1 - u * u)) / rho;
      mesh.point(v) = to_point(Eigen::Vector3d(p.x(), p.y() * scale, p.z() * scale));
    }
  }
  return meshes.emplace(vertices, std::move(mesh)).first->second;
}

void BM_LocalSurgery(benchmark::State& state)
{
  const Mesh& mesh = pinched_dumbbell(static_cast<int>(state.range(0)));
  const std::vector<FacePair> crossings = self_intersections(mesh);
  int components = 0, patch = 0, attempts = 0;
  for (auto _ : state) {
    const LocalSurgery local = local_surgery(mesh, crossings, {});
    if (!local.result) {
      state.SkipWithError(local.failure.c_str());
      return;
    }
    components = local.result->components_after;
    patch = local.result->patch_faces;
    attempts = local.attempts;
  }
  state.counters["faces"] = static_cast<double>(mesh.n_faces());
  state.counters["patch_faces"] = patch;
  state.counters["components"] = components;
  state.counters["attempts"] = attempts;
}

void BM_GlobalPipeline(benchmark::State& state)
{
  const Mesh& mesh = pinched_dumbbell(static_cast<int>(state.range(0)));
  int components = 0;
  for (auto _ : state)
    components = retriangulate(mesh, {}).components_after;
  state.counters["pairs"] = static_cast<double>(self_intersections(mesh).size());
  state.counters["faces"] = static_cast<double>(mesh.n_faces());
  state.counters["components"] = components;
}

//! What the hook pays beforehand in either case: finding the crossings (it keeps them from its check).
void BM_SelfIntersections(benchmark::State& state)
{
  const Mesh& mesh = pinched_dumbbell(static_cast<int>(state.range(0)));
  std::size_t pairs = 0;
  for (auto _ : state)
    pairs = self_intersections(mesh).size();
  state.counters["pairs"] = static_cast<double>(pairs);
}

} // namespace

BENCHMARK(BM_LocalSurgery)->Arg(20000)->Arg(100000)->Arg(150000)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
BENCHMARK(BM_GlobalPipeline)->Arg(20000)->Arg(100000)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
BENCHMARK(BM_SelfIntersections)->Arg(20000)->Arg(100000)->Unit(benchmark::kMillisecond)->UseRealTime()->MeasureProcessCPUTime();
BENCHMARK_MAIN();
