#include "sdflow/geometry/principal_curvature.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/angle.h"
#include "sdflow/geometry/detail/mixed_voronoi.h"
#include "sdflow/geometry/normals.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace sdflow {
namespace {

//! The angle of the corner at `p` between the edges to `a` and `b`.
double corner_angle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
  return angle_between(a - p, b - p);
}

//! The sum of the corner angles at each vertex.
Eigen::VectorXd vertex_angle_sums(const Mesh& mesh)
{
  Eigen::VectorXd angle_sums = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(mesh.n_vertices()));
  for (auto f : mesh.faces()) {
    const TriangleCorners t = triangle_corners(mesh, f);
    for (int c = 0; c < 3; ++c)
      angle_sums[t.index[c]] += corner_angle(t.point[c], t.point[(c + 1) % 3], t.point[(c + 2) % 3]);
  }
  return angle_sums;
}

//! Whether vertex v carries a curvature: interior, with area.
bool curved(const Mesh& mesh, Mesh::VertexHandle v, const Eigen::VectorXd& areas)
{
  return !mesh.is_boundary(v) && areas[v.idx()] > 0;
}

//! K = (2π − Σα)/A at vertex i.
double angle_defect(double angle_sum, double area) { return (2 * std::numbers::pi - angle_sum) / area; }

//! κ = |H| + √max(H² − K, 0) with K = (2π − Σα)/A at interior vertices with area; boundary vertices
//! take the largest κ of their interior neighbours, the others 0.
Eigen::VectorXd kappa_from(const Mesh& mesh, const Eigen::VectorXd& mean_curvature, const Eigen::VectorXd& areas,
                           const Eigen::VectorXd& angle_sums)
{
  Eigen::VectorXd kappa = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(mesh.n_vertices()));
  for (auto v : mesh.vertices()) {
    const int i = v.idx();
    if (!curved(mesh, v, areas))
      continue;
    const double gaussian = angle_defect(angle_sums[i], areas[i]);
    const double h = mean_curvature[i];
    kappa[i] = std::abs(h) + std::sqrt(std::max(h * h - gaussian, 0.0));
  }
  for (auto v : mesh.vertices())
    if (mesh.is_boundary(v))
      for (auto w : mesh.vv_range(v))
        if (!mesh.is_boundary(w))
          kappa[v.idx()] = std::max(kappa[v.idx()], kappa[w.idx()]);
  return kappa;
}

} // namespace

Eigen::VectorXd gaussian_curvature(const Mesh& mesh, const Eigen::VectorXd& areas)
{
  const Eigen::VectorXd angle_sums = vertex_angle_sums(mesh);
  Eigen::VectorXd gaussian = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(mesh.n_vertices()));
  for (auto v : mesh.vertices())
    if (curved(mesh, v, areas))
      gaussian[v.idx()] = angle_defect(angle_sums[v.idx()], areas[v.idx()]);
  return gaussian;
}

Eigen::VectorXd largest_principal_curvature(const Mesh& mesh, const Eigen::VectorXd& mean_curvature,
                                            const Eigen::VectorXd& areas)
{
  return kappa_from(mesh, mean_curvature, areas, vertex_angle_sums(mesh));
}

Eigen::VectorXd largest_principal_curvature(const Mesh& mesh)
{
  // One pass over the faces gathers what cotangent_laplacian, mixed_voronoi_areas and the angle
  // sums would: L X without assembling L, the areas and the corner angles. A re-triangulating run
  // evaluates this after every step (radius_targets), so the sparse assembly mattered.
  const auto n = static_cast<Eigen::Index>(mesh.n_vertices());
  VertexVectors laplacian_x = VertexVectors::Zero(n, 3);
  Eigen::VectorXd areas = Eigen::VectorXd::Zero(n), angle_sums = Eigen::VectorXd::Zero(n);
  for (auto f : mesh.faces()) {
    const TriangleCorners t = triangle_corners(mesh, f);
    const double twice_area = (t.point[1] - t.point[0]).cross(t.point[2] - t.point[0]).norm();
    if (!(twice_area > 0))
      throw InvalidMesh(fmt::format("largest_principal_curvature: triangle {} has zero area", f.idx()));
    std::array<double, 3> dots{};
    for (int c = 0; c < 3; ++c) {
      const int j = t.index[(c + 1) % 3], k = t.index[(c + 2) % 3];
      const Eigen::Vector3d a = t.point[(c + 1) % 3] - t.point[c];
      const Eigen::Vector3d b = t.point[(c + 2) % 3] - t.point[c];
      dots[c] = a.dot(b);
      const double half_cot = 0.5 * dots[c] / twice_area; // the cotangent weight of edge jk, halved
      const Eigen::Vector3d edge = t.point[(c + 2) % 3] - t.point[(c + 1) % 3];
      laplacian_x.row(j) += half_cot * edge.transpose();
      laplacian_x.row(k) -= half_cot * edge.transpose();
      angle_sums[t.index[c]] += angle_between(a, b);
    }
    detail::add_mixed_voronoi_areas(t.point, t.index, dots, twice_area, areas);
  }
  const VertexVectors normals = vertex_normals(mesh);
  Eigen::VectorXd h = Eigen::VectorXd::Zero(n);
  for (auto v : mesh.vertices()) {
    const int i = v.idx();
    if (mesh.is_boundary(v))
      continue;
    if (!(areas[i] > 0))
      throw InvalidMesh(
          fmt::format("largest_principal_curvature: vertex {} has no area (isolated or degenerate star)", i));
    h[i] = 0.5 * normals.row(i).dot(laplacian_x.row(i)) / areas[i];
  }
  return kappa_from(mesh, h, areas, angle_sums);
}

} // namespace sdflow
