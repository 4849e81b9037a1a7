//! Side by side, in one run: CGAL's PMP::self_intersections (sequential, Epick) and sdflow's
//! self_intersections / refit-based tracker on the same 100k-vertex sphere (bench/cube_sphere.h),
//! smooth and with its cap pushed through itself. Before timing, the pair sets are compared and
//! the program exits with status 1 if they differ.
#include "cube_sphere.h"

#include "sdflow/spatial/intersect.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <benchmark/benchmark.h>

#include <algorithm>
#include <iostream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Face = boost::graph_traits<CgalMesh>::face_descriptor;
using namespace sdflow;

//! Same vertices and faces in the same order, so CGAL's face indices are sdflow's.
CgalMesh to_cgal(const Mesh& mesh)
{
  CgalMesh out;
  for (auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    out.add_vertex(Kernel::Point_3(p[0], p[1], p[2]));
  }
  for (auto f : mesh.faces()) {
    std::vector<CgalMesh::Vertex_index> corners;
    for (auto v : mesh.fv_range(f))
      corners.emplace_back(v.idx());
    out.add_face(corners);
  }
  return out;
}

std::vector<FacePair> cgal_pairs(const CgalMesh& mesh)
{
  std::vector<std::pair<Face, Face>> found;
  CGAL::Polygon_mesh_processing::self_intersections(mesh, std::back_inserter(found));
  std::vector<FacePair> pairs;
  for (const auto& [f, g] : found)
    pairs.push_back({static_cast<int>(std::min(f.idx(), g.idx())), static_cast<int>(std::max(f.idx(), g.idx()))});
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

struct Input {
  Mesh mesh;
  CgalMesh cgal;
};

const Input& sphere()
{
  static const Input input = [] {
    Mesh m = bench::cube_sphere(129);
    return Input{m, to_cgal(m)};
  }();
  return input;
}

const Input& pushed()
{
  static const Input input = [] {
    Mesh m = bench::pushed_through(bench::cube_sphere(129));
    return Input{m, to_cgal(m)};
  }();
  return input;
}

void BM_Cgal_SelfIntersections(benchmark::State& state, const Input* input)
{
  std::size_t pairs = 0;
  for (auto _ : state)
    pairs = cgal_pairs(input->cgal).size();
  state.counters["pairs"] = static_cast<double>(pairs);
}

void BM_Sdflow_SelfIntersections(benchmark::State& state, const Input* input, Execution execution)
{
  std::size_t pairs = 0;
  for (auto _ : state)
    pairs = self_intersections(input->mesh, {.execution = execution}).size();
  state.counters["pairs"] = static_cast<double>(pairs);
}

//! A smooth step along the normals (amplitude 2e-4 of the radius, a sixtieth of an edge)
//! re-checked by the tracker: refit and re-test.
void BM_Sdflow_TrackerSmoothStep(benchmark::State& state, const Input* input, Execution execution)
{
  SelfIntersectionTracker tracker(input->mesh, {.execution = execution});
  const VertexVectors a = bench::smooth_step(input->mesh, 2e-4), b = bench::smooth_step(input->mesh, -2e-4);
  bool flip = false;
  std::size_t pairs = 0;
  for (auto _ : state)
    pairs = tracker.update((flip = !flip) ? a : b).size();
  state.counters["pairs"] = static_cast<double>(pairs);
}

//! Independent noise on every coordinate (1e-4 of the radius, a hundredth of an edge): adjacent
//! faces become nearly coplanar at random, the hard case for the re-check.
void BM_Sdflow_TrackerNoisyStep(benchmark::State& state, const Input* input, Execution execution)
{
  SelfIntersectionTracker tracker(input->mesh, {.execution = execution});
  const VertexVectors a = bench::jiggled(input->mesh, 1e-4, 4), b = bench::jiggled(input->mesh, 1e-4, 5);
  bool flip = false;
  std::size_t pairs = 0;
  for (auto _ : state)
    pairs = tracker.update((flip = !flip) ? a : b).size();
  state.counters["pairs"] = static_cast<double>(pairs);
}

bool same_results(const char* name, const Input& input)
{
  const auto ours = self_intersections(input.mesh);
  const auto theirs = cgal_pairs(input.cgal);
  std::cerr << name << ": sdflow " << ours.size() << " pairs, CGAL " << theirs.size() << " pairs, "
            << (ours == theirs ? "identical" : "DIFFERENT") << '\n';
  return ours == theirs;
}

} // namespace

int main(int argc, char** argv)
{
  const bool same = same_results("sphere", sphere()) & same_results("pushed-through sphere", pushed());
  if (!same)
    return 1;
  for (const auto& [name, input] : {std::pair{"sphere", &sphere()}, std::pair{"pushed", &pushed()}}) {
    const std::string tag = std::string("/") + name;
    benchmark::RegisterBenchmark(("Cgal_SelfIntersections" + tag).c_str(), BM_Cgal_SelfIntersections, input)
      ->Unit(benchmark::kMillisecond);
    for (const auto& [mode, execution] :
         {std::pair{"Sequential", Execution::sequential}, std::pair{"Parallel", Execution::parallel}}) {
      benchmark::RegisterBenchmark(("Sdflow_SelfIntersections" + std::string(mode) + tag).c_str(),
                                   BM_Sdflow_SelfIntersections, input, execution)
        ->Unit(benchmark::kMillisecond);
      benchmark::RegisterBenchmark(("Sdflow_TrackerSmoothStep" + std::string(mode) + tag).c_str(),
                                   BM_Sdflow_TrackerSmoothStep, input, execution)
        ->Unit(benchmark::kMillisecond);
      benchmark::RegisterBenchmark(("Sdflow_TrackerNoisyStep" + std::string(mode) + tag).c_str(),
                                   BM_Sdflow_TrackerNoisyStep, input, execution)
        ->Unit(benchmark::kMillisecond);
    }
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
