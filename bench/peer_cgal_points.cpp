//! CGAL on the inputs of bench_points (benchmark peer only): jet_estimate_normals (k = 18,
//! sequential), mst_orient_normals (k = 18), both, and Advancing Front Surface Reconstruction
//! with its defaults (radius_ratio_bound 5, beta 0.52, as sdflow's).
//! Run: build/bench/peer_cgal_points --benchmark_repetitions=3 --benchmark_report_aggregates_only=true

#include "point_inputs.h"

#include <CGAL/Advancing_front_surface_reconstruction.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/jet_estimate_normals.h>
#include <CGAL/mst_orient_normals.h>
#include <CGAL/property_map.h>
#include <benchmark/benchmark.h>

#include <array>
#include <iterator>
#include <utility>
#include <vector>

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Vector = Kernel::Vector_3;
using PointWithNormal = std::pair<Point, Vector>;

const sdflow::bench::PointInput& input(const benchmark::State& state)
{
  return sdflow::bench::point_inputs()[static_cast<std::size_t>(state.range(0))];
}

std::vector<PointWithNormal> cgal_points(const sdflow::bench::PointInput& in)
{
  std::vector<PointWithNormal> v;
  v.reserve(static_cast<std::size_t>(in.points.rows()));
  for (Eigen::Index i = 0; i < in.points.rows(); ++i)
    v.emplace_back(Point(in.points(i, 0), in.points(i, 1), in.points(i, 2)), Vector(0, 0, 0));
  return v;
}

auto maps()
{
  return CGAL::parameters::point_map(CGAL::First_of_pair_property_map<PointWithNormal>())
      .normal_map(CGAL::Second_of_pair_property_map<PointWithNormal>());
}

void BM_CgalJetNormals(benchmark::State& state)
{
  const auto& in = input(state);
  for (auto _ : state) {
    state.PauseTiming();
    auto points = cgal_points(in);
    state.ResumeTiming();
    CGAL::jet_estimate_normals<CGAL::Sequential_tag>(points, sdflow::bench::bench_neighbours, maps());
    benchmark::DoNotOptimize(points.data());
  }
  state.SetLabel(in.name);
}

void BM_CgalMstOrientation(benchmark::State& state)
{
  const auto& in = input(state);
  auto estimated = cgal_points(in);
  CGAL::jet_estimate_normals<CGAL::Sequential_tag>(estimated, sdflow::bench::bench_neighbours, maps());
  std::ptrdiff_t unoriented = 0;
  for (auto _ : state) {
    state.PauseTiming();
    auto points = estimated;
    state.ResumeTiming();
    const auto first_unoriented = CGAL::mst_orient_normals(points, sdflow::bench::bench_neighbours, maps());
    unoriented = std::distance(first_unoriented, points.end());
  }
  state.counters["unoriented"] = static_cast<double>(unoriented);
  state.SetLabel(in.name);
}

void BM_CgalJetAndMst(benchmark::State& state)
{
  const auto& in = input(state);
  std::ptrdiff_t unoriented = 0;
  for (auto _ : state) {
    state.PauseTiming();
    auto points = cgal_points(in);
    state.ResumeTiming();
    CGAL::jet_estimate_normals<CGAL::Sequential_tag>(points, sdflow::bench::bench_neighbours, maps());
    const auto first_unoriented = CGAL::mst_orient_normals(points, sdflow::bench::bench_neighbours, maps());
    unoriented = std::distance(first_unoriented, points.end());
  }
  state.counters["unoriented"] = static_cast<double>(unoriented);
  state.SetLabel(in.name);
}

void BM_CgalAdvancingFront(benchmark::State& state)
{
  const auto& in = input(state);
  std::vector<Point> points;
  for (const auto& [p, n] : cgal_points(in))
    points.push_back(p);
  std::size_t faces = 0;
  for (auto _ : state) {
    std::vector<std::array<std::size_t, 3>> triangles;
    CGAL::advancing_front_surface_reconstruction(points.begin(), points.end(), std::back_inserter(triangles));
    faces = triangles.size();
  }
  state.counters["faces"] = static_cast<double>(faces);
  state.SetLabel(in.name);
}

void arguments(benchmark::internal::Benchmark* b)
{
  b->ArgNames({"input"})->Unit(benchmark::kMillisecond)->Iterations(1)->Arg(0)->Arg(1);
}

BENCHMARK(BM_CgalJetNormals)->Apply(arguments);
BENCHMARK(BM_CgalMstOrientation)->Apply(arguments);
BENCHMARK(BM_CgalJetAndMst)->Apply(arguments);
BENCHMARK(BM_CgalAdvancingFront)->Apply(arguments);

} // namespace

BENCHMARK_MAIN();
