//! BVH build, refit and closest-point queries, self-intersection check and tracker re-check on
//! the 100k-vertex sphere (bench/cube_sphere.h), all on one thread so that CPU times compare. The
//! CGAL side-by-side run (and the threaded variants) is peer_cgal_intersections.cpp.
#include "cube_sphere.h"

#include "sdflow/spatial/bvh.h"
#include "sdflow/spatial/intersect.h"

#include <benchmark/benchmark.h>

namespace {

using namespace sdflow;

const Mesh& sphere()
{
  static const Mesh mesh = bench::cube_sphere(129);
  return mesh;
}

const Mesh& pushed()
{
  static const Mesh mesh = bench::pushed_through(sphere());
  return mesh;
}

void BM_BvhBuild(benchmark::State& state)
{
  for (auto _ : state) {
    Bvh tree(sphere());
    benchmark::DoNotOptimize(tree.node_count());
  }
  state.counters["faces"] = static_cast<double>(sphere().n_faces());
}

void BM_BvhRefit(benchmark::State& state)
{
  Bvh tree(sphere());
  const VertexVectors a = bench::jiggled(sphere(), 1e-5, 1), b = bench::jiggled(sphere(), 1e-5, 2);
  bool flip = false;
  for (auto _ : state) {
    tree.refit((flip = !flip) ? a : b);
    benchmark::DoNotOptimize(tree.bounds());
  }
}

void BM_BvhClosestPoint(benchmark::State& state)
{
  // Projection of perturbed vertices back onto the surface, as the remesher does.
  const Bvh tree(sphere());
  const VertexVectors q = bench::jiggled(sphere(), 1e-3, 3);
  for (auto _ : state)
    for (Eigen::Index v = 0; v < q.rows(); ++v)
      benchmark::DoNotOptimize(tree.closest_point(q.row(v).transpose()).face);
  state.counters["queries"] = static_cast<double>(q.rows());
}

void self_intersection_check(benchmark::State& state, const Mesh& mesh)
{
  std::size_t pairs = 0;
  for (auto _ : state)
    pairs = self_intersections(mesh, {.execution = Execution::sequential}).size();
  state.counters["pairs"] = static_cast<double>(pairs);
}

void BM_SelfIntersections_Sphere(benchmark::State& state) { self_intersection_check(state, sphere()); }
void BM_SelfIntersections_PushedThrough(benchmark::State& state) { self_intersection_check(state, pushed()); }

//! Re-check after a smooth step along the normals (2e-4 of the radius, a sixtieth of an edge): the
//! cached candidates stay valid, only the tree is refitted and the pairs re-tested.
void BM_TrackerUpdate_SmoothStep(benchmark::State& state)
{
  SelfIntersectionTracker tracker(sphere(), {.execution = Execution::sequential});
  const VertexVectors a = bench::smooth_step(sphere(), 2e-4), b = bench::smooth_step(sphere(), -2e-4);
  bool flip = false;
  for (auto _ : state)
    benchmark::DoNotOptimize(tracker.update((flip = !flip) ? a : b).size());
  state.counters["collections"] = tracker.collections();
  state.counters["candidates"] = tracker.candidate_count();
}

//! Re-check after independent noise of 1e-4 of the radius on every coordinate (a hundredth of an
//! edge): adjacent faces turn nearly coplanar at random, the hard case.
void BM_TrackerUpdate_NoisyStep(benchmark::State& state)
{
  SelfIntersectionTracker tracker(sphere(), {.execution = Execution::sequential});
  const VertexVectors a = bench::jiggled(sphere(), 1e-4, 4), b = bench::jiggled(sphere(), 1e-4, 5);
  bool flip = false;
  for (auto _ : state)
    benchmark::DoNotOptimize(tracker.update((flip = !flip) ? a : b).size());
  state.counters["collections"] = tracker.collections();
  state.counters["candidates"] = tracker.candidate_count();
}

//! Re-check after a step larger than the margin: refit, new candidates, test.
void BM_TrackerUpdate_LargeStep(benchmark::State& state)
{
  SelfIntersectionTracker tracker(sphere(), {.execution = Execution::sequential});
  VertexVectors a = vertex_positions(sphere()), b = a * 1.02;
  bool flip = false;
  for (auto _ : state)
    benchmark::DoNotOptimize(tracker.update((flip = !flip) ? b : a).size());
  state.counters["collections"] = tracker.collections();
}

} // namespace

BENCHMARK(BM_BvhBuild)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BvhRefit)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BvhClosestPoint)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SelfIntersections_Sphere)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SelfIntersections_PushedThrough)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TrackerUpdate_SmoothStep)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TrackerUpdate_NoisyStep)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TrackerUpdate_LargeStep)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
