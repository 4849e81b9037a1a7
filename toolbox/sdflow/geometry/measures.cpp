#include "sdflow/geometry/measures.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/topology.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sdflow {

double cone_volume(const Mesh& mesh, Mesh::FaceHandle f)
{
  auto h = mesh.halfedge_handle(f);
  const Eigen::Vector3d a = to_eigen(mesh.point(mesh.from_vertex_handle(h)));
  const Eigen::Vector3d b = to_eigen(mesh.point(mesh.to_vertex_handle(h)));
  const Eigen::Vector3d c = to_eigen(mesh.point(mesh.to_vertex_handle(mesh.next_halfedge_handle(h))));
  return cone_volume(a, b, c);
}

double surface_area(const Mesh& mesh)
{
  double area = 0;
  for (auto f : mesh.faces())
    area += mesh.calc_face_area(f);
  return area;
}

double enclosed_volume(const Mesh& mesh)
{
  double volume = 0;
  for (auto f : mesh.faces())
    volume += cone_volume(mesh, f);
  return volume;
}

std::vector<double> component_volumes(const Mesh& mesh)
{
  int count = 0;
  const std::vector<int> id = face_component_ids(mesh, &count);
  std::vector<double> volumes(count, 0.0);
  for (auto f : mesh.faces())
    volumes[id[f.idx()]] += cone_volume(mesh, f);
  return volumes;
}

std::vector<double> component_volumes(const VertexVectors& positions, const FaceIndices& triangles,
                                      const std::vector<int>& face_component, int count)
{
  std::vector<double> volume(count, 0.0);
  for (Eigen::Index f = 0; f < triangles.rows(); ++f) {
    const Eigen::Vector3d a = positions.row(triangles(f, 0)), b = positions.row(triangles(f, 1)),
                          c = positions.row(triangles(f, 2));
    volume[face_component[f]] += cone_volume(a, b, c);
  }
  return volume;
}

CurvatureDeviation curvature_deviation(const Eigen::VectorXd& curvature, const Eigen::VectorXd& vertex_areas)
{
  if (curvature.size() != vertex_areas.size())
    throw InvalidParameter(fmt::format("curvature_deviation: {} curvatures for {} areas", curvature.size(),
                                       vertex_areas.size()));
  const double total = vertex_areas.sum();
  if (!(total > 0))
    throw InvalidParameter("curvature_deviation: the vertex areas sum to zero");
  CurvatureDeviation d;
  d.mean = curvature.dot(vertex_areas) / total;
  d.deviation = (curvature.array() - d.mean).abs().matrix().dot(vertex_areas) / total;
  d.deviation_pct = d.mean != 0 ? 100.0 * d.deviation / std::abs(d.mean) : std::numeric_limits<double>::infinity();
  return d;
}

SphereDeviation sphere_deviation(const Mesh& mesh, const Eigen::VectorXd& vertex_areas,
                                 const Eigen::Vector3d& centre, double radius)
{
  if (vertex_areas.size() != static_cast<Eigen::Index>(mesh.n_vertices()))
    throw InvalidParameter("sphere_deviation: one area per vertex is needed");
  if (!(radius > 0))
    throw InvalidParameter(fmt::format("sphere_deviation: radius must be positive, got {}", radius));
  Eigen::VectorXd gap(mesh.n_vertices());
  for (auto v : mesh.vertices())
    gap[v.idx()] = std::abs((to_eigen(mesh.point(v)) - centre).norm() - radius);
  // §4.4 normalises by A(S^n), the surface area, which equals Σ A(U_i) for mixed Voronoi areas.
  const double total = vertex_areas.sum();
  SphereDeviation d;
  d.d1 = gap.dot(vertex_areas) / total;
  d.d2 = (gap.array() - d.d1).abs().matrix().dot(vertex_areas) / total;
  return d;
}

double mean_edge_length(const Mesh& mesh)
{
  double sum = 0;
  for (const auto e : mesh.edges())
    sum += mesh.calc_edge_length(e);
  return sum / static_cast<double>(std::max<std::size_t>(mesh.n_edges(), 1));
}

double mean_edge_length_at(const Mesh& mesh, Mesh::VertexHandle v)
{
  double sum = 0;
  int count = 0;
  for (const auto h : mesh.voh_range(v)) {
    sum += mesh.calc_edge_length(h);
    ++count;
  }
  return count > 0 ? sum / count : 0;
}

Eigen::VectorXd vertex_mean_edge_lengths(const Mesh& mesh)
{
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(mesh.n_vertices());
  Eigen::VectorXd count = Eigen::VectorXd::Zero(mesh.n_vertices());
  for (const auto e : mesh.edges()) {
    const double length = mesh.calc_edge_length(e);
    const int a = e.v0().idx(), b = e.v1().idx();
    sum[a] += length;
    sum[b] += length;
    count[a] += 1;
    count[b] += 1;
  }
  return sum.cwiseQuotient(count.cwiseMax(1.0));
}

} // namespace sdflow
