//! Side by side, in one run: CGAL's PMP::isotropic_remeshing and sdflow's isotropic_remesh (both
//! Botsch & Kobbelt 2004, both projecting the vertices onto the input triangles), 3 iterations to
//! the same ℓ on a 100k-vertex sphere (bench/cube_sphere.h) and a 100k-vertex torus (R = 6,
//! r = 3, a 400 × 250 grid of the angles, so its edges range over a factor 3), at ℓ = 1.0 and
//! 0.8 × the input's mean edge length. sdflow runs with its default of 3 relaxation sweeps per
//! iteration and with CGAL's default of 1 (relax:1), on 1 and 2 TBB threads. The counters give
//! each result's quality, measured by the same code outside the timing: vertices, share of edges
//! within [4/5, 4/3] ℓ, minimum angle and its 5th percentile (degrees), largest distance of a
//! vertex to the analytic surface and to the input triangles.
//! Run: build/bench/peer_cgal_remesh --benchmark_repetitions=3 --benchmark_report_aggregates_only=true

#include "cube_sphere.h"
#include "support/analytic_meshes.h"

#include "sdflow/remesh/remesh.h"
#include "sdflow/shapes/mesher.h"
#include "sdflow/spatial/bvh.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Surface_mesh.h>
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using namespace sdflow;

constexpr int kIterations = 3;
constexpr double kTorusMajor = 6, kTorusMinor = 3;

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

//! CGAL's result as an sdflow mesh, so that both are measured by the same code.
Mesh from_cgal(CgalMesh mesh)
{
  mesh.collect_garbage();
  VertexVectors x(mesh.number_of_vertices(), 3);
  for (auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    x.row(v.idx()) << p.x(), p.y(), p.z();
  }
  sdflow::FaceIndices t(mesh.number_of_faces(), 3);
  for (auto f : mesh.faces()) {
    int k = 0;
    for (auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh))
      t(f.idx(), k++) = static_cast<int>(v.idx());
  }
  return make_mesh(x, t);
}

double mean_edge_length(const Mesh& mesh)
{
  double sum = 0;
  for (auto e : mesh.edges())
    sum += mesh.calc_edge_length(e);
  return sum / mesh.n_edges();
}

struct Input {
  const char* name;
  Mesh mesh;
  CgalMesh cgal;
  Bvh tree; //!< of the input triangles, to measure distances to them
  double mean_edge;
  std::function<double(const Eigen::Vector3d&)> analytic_distance;
};

Input make_input(const char* name, Mesh mesh, std::function<double(const Eigen::Vector3d&)> distance)
{
  CgalMesh cgal = to_cgal(mesh);
  Bvh tree(mesh);
  const double mean = mean_edge_length(mesh);
  return {name, std::move(mesh), std::move(cgal), std::move(tree), mean, std::move(distance)};
}

const std::vector<Input>& inputs()
{
  static const std::vector<Input> all = [] {
    std::vector<Input> v;
    v.push_back(make_input("sphere", bench::cube_sphere(129),
                           [](const Eigen::Vector3d& p) { return std::abs(p.norm() - 1); }));
    v.push_back(make_input("torus", analytic::torus(400, 250, kTorusMajor, kTorusMinor), [](const Eigen::Vector3d& p) {
      return std::abs(std::hypot(std::hypot(p.x(), p.y()) - kTorusMajor, p.z()) - kTorusMinor);
    }));
    return v;
  }();
  return all;
}

struct Case {
  const Input* input;
  double scale; //!< ℓ / the input's mean edge length
  double ell() const { return scale * input->mean_edge; }
};

RemeshOptions sdflow_options(const Case& c, int relaxation_steps)
{
  return {.edge_length = c.ell(), .iterations = kIterations, .relaxation_steps = relaxation_steps};
}

struct Quality {
  std::size_t vertices = 0;
  double band_share = 0;     //!< edges within [4/5, 4/3] ℓ
  double min_angle = 0;      //!< degrees
  double min_angle_p05 = 0;  //!< 5th percentile of the per-triangle minimum angle
  double analytic_distance = 0; //!< largest vertex distance to the sphere or torus
  double input_distance = 0;    //!< largest vertex distance to the input triangles
};

Quality quality(const Mesh& mesh, const Case& c)
{
  Quality q;
  q.vertices = mesh.n_vertices();
  long in_band = 0;
  for (auto e : mesh.edges()) {
    const double r = mesh.calc_edge_length(e) / c.ell();
    in_band += r >= 0.8 && r <= 4.0 / 3.0;
  }
  q.band_share = static_cast<double>(in_band) / mesh.n_edges();
  const AngleDistribution angles = triangle_min_angle_distribution(mesh);
  q.min_angle = angles.min;
  q.min_angle_p05 = angles.p05;
  for (auto v : mesh.vertices()) {
    const Eigen::Vector3d p = to_eigen(mesh.point(v));
    q.analytic_distance = std::max(q.analytic_distance, c.input->analytic_distance(p));
    q.input_distance = std::max(q.input_distance, std::sqrt(c.input->tree.closest_point(p).squared_distance));
  }
  return q;
}

void counters(benchmark::State& state, const Quality& q)
{
  state.counters["vertices"] = static_cast<double>(q.vertices);
  state.counters["in_band"] = q.band_share;
  state.counters["min_angle"] = q.min_angle;
  state.counters["min_angle_p05"] = q.min_angle_p05;
  state.counters["to_surface"] = q.analytic_distance;
  state.counters["to_input"] = q.input_distance;
}

void BM_Cgal_Remesh(benchmark::State& state, Case c)
{
  Mesh result;
  for (auto _ : state) {
    state.PauseTiming();
    CgalMesh mesh = c.input->cgal;
    state.ResumeTiming();
    CGAL::Polygon_mesh_processing::isotropic_remeshing(faces(mesh), c.ell(), mesh,
                                                       CGAL::parameters::number_of_iterations(kIterations));
    state.PauseTiming();
    result = from_cgal(std::move(mesh));
    state.ResumeTiming();
  }
  counters(state, quality(result, c));
}

//! sdflow with `relaxation_steps` relaxation sweeps per iteration (its default is 3, CGAL's 1) on
//! state.range(0) TBB threads.
void BM_Sdflow_Remesh(benchmark::State& state, Case c, int relaxation_steps)
{
  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(state.range(0)));
  RemeshResult result;
  for (auto _ : state)
    result = isotropic_remesh(c.input->mesh, sdflow_options(c, relaxation_steps));
  counters(state, quality(result.mesh, c));
}

} // namespace

int main(int argc, char** argv)
{
  benchmark::Initialize(&argc, argv);
  std::vector<Case> cases;
  for (const Input& input : inputs())
    for (double scale : {1.0, 0.8})
      cases.push_back({&input, scale});
  for (const Case& c : cases) {
    char tag[64];
    std::snprintf(tag, sizeof tag, "/%s/ell:%.1f", c.input->name, c.scale);
    benchmark::RegisterBenchmark((std::string("Cgal_Remesh") + tag).c_str(), BM_Cgal_Remesh, c)
        ->Unit(benchmark::kMillisecond);
    for (int relaxation : {3, 1})
      benchmark::RegisterBenchmark(
          (std::string("Sdflow_Remesh") + tag + "/relax:" + std::to_string(relaxation)).c_str(), BM_Sdflow_Remesh,
          c, relaxation)
          ->ArgName("threads")
          ->Arg(1)
          ->Arg(2)
          ->Unit(benchmark::kMillisecond);
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
