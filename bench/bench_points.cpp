//! Point normals and reconstruction on 100k points (bench/point_inputs.h): jet normals (k = 18),
//! MST orientation, both together as the pipeline runs them, and advancing-front reconstruction.
//! Second argument: worker threads (TBB). peer_cgal_points runs CGAL on the same inputs.
//! Run: build/bench/bench_points --benchmark_repetitions=3 --benchmark_report_aggregates_only=true

#include "point_inputs.h"

#include "sdflow/reconstruct/advancing_front.h"
#include "sdflow/reconstruct/point_normals.h"

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

namespace {

using namespace sdflow;

const bench::PointInput& input(const benchmark::State& state)
{
  return bench::point_inputs()[static_cast<std::size_t>(state.range(0))];
}

tbb::global_control threads(const benchmark::State& state)
{
  return tbb::global_control(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(1)));
}

void BM_JetNormals(benchmark::State& state)
{
  const auto& in = input(state);
  const auto control = threads(state);
  for (auto _ : state) {
    const VertexVectors normals = jet_normals(in.points, nearest_neighbours(in.points, bench::bench_neighbours));
    benchmark::DoNotOptimize(normals.data());
  }
  state.SetLabel(in.name);
}

// Includes its own k-NN search, as CGAL's mst_orient_normals does.
void BM_MstOrientation(benchmark::State& state)
{
  const auto& in = input(state);
  const auto control = threads(state);
  const VertexVectors unoriented = jet_normals(in.points, nearest_neighbours(in.points, bench::bench_neighbours));
  std::size_t inconsistent = 0;
  for (auto _ : state) {
    const NormalOrientation o =
        orient_normals(in.points, unoriented, nearest_neighbours(in.points, bench::bench_neighbours));
    inconsistent = o.inconsistent.size();
  }
  state.counters["inconsistent"] = static_cast<double>(inconsistent);
  state.SetLabel(in.name);
}

// The whole estimation as the pipeline calls it: one k-NN search shared by fit and orientation.
void BM_JetAndMst(benchmark::State& state)
{
  const auto& in = input(state);
  const auto control = threads(state);
  PointNormalsOptions options;
  options.neighbours = bench::bench_neighbours;
  std::size_t removed = 0;
  for (auto _ : state)
    removed = oriented_point_normals(in.points, options).removed.size();
  state.counters["removed"] = static_cast<double>(removed);
  state.SetLabel(in.name);
}

void BM_Reconstruct(benchmark::State& state)
{
  const auto& in = input(state);
  const auto control = threads(state);
  std::size_t faces = 0;
  for (auto _ : state)
    faces = reconstruct_surface(in.points, in.normals).mesh.n_faces();
  state.counters["faces"] = static_cast<double>(faces);
  state.SetLabel(in.name);
}

void arguments(benchmark::internal::Benchmark* b)
{
  b->ArgNames({"input", "threads"})->Unit(benchmark::kMillisecond)->Iterations(1);
  for (int i = 0; i < 2; ++i)
    for (int t : {1, 2})
      b->Args({i, t});
}

BENCHMARK(BM_JetNormals)->Apply(arguments);
BENCHMARK(BM_MstOrientation)->Apply(arguments);
BENCHMARK(BM_JetAndMst)->Apply(arguments);
BENCHMARK(BM_Reconstruct)->Apply(arguments);

} // namespace

BENCHMARK_MAIN();
