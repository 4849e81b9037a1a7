#include "sdflow/geometry/quality.h"

#include "sdflow/geometry/angle.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace sdflow {

std::array<double, 3> corner_angles(const Mesh& mesh, Mesh::FaceHandle f)
{
  const std::array<Eigen::Vector3d, 3> p = triangle_corners(mesh, f).point;
  std::array<double, 3> angles{};
  for (int c = 0; c < 3; ++c) {
    const Eigen::Vector3d a = p[(c + 1) % 3] - p[c], b = p[(c + 2) % 3] - p[c];
    angles[c] = angle_between(a, b);
  }
  return angles;
}

namespace {

//! The two sides at face f's smallest corner, which faces the shortest side (law of sines): one
//! angle to measure instead of three, as the per-step look at the surface measures every triangle.
std::array<Eigen::Vector3d, 2> sides_at_smallest_angle(const Mesh& mesh, Mesh::FaceHandle f)
{
  const std::array<Eigen::Vector3d, 3> p = triangle_corners(mesh, f).point;
  int corner = 0;
  double shortest = std::numeric_limits<double>::infinity();
  for (int c = 0; c < 3; ++c)
    if (const double opposite = (p[(c + 2) % 3] - p[(c + 1) % 3]).squaredNorm(); opposite < shortest) {
      shortest = opposite;
      corner = c;
    }
  return {p[(corner + 1) % 3] - p[corner], p[(corner + 2) % 3] - p[corner]};
}

} // namespace

double smallest_angle_deg(const Mesh& mesh, Mesh::FaceHandle f)
{
  const auto [a, b] = sides_at_smallest_angle(mesh, f);
  return angle_between(a, b) * 180 / std::numbers::pi;
}

double smallest_angle_cosine(const Mesh& mesh, Mesh::FaceHandle f)
{
  const auto [a, b] = sides_at_smallest_angle(mesh, f);
  const double lengths = std::sqrt(a.squaredNorm() * b.squaredNorm());
  return lengths > 0 ? std::clamp(a.dot(b) / lengths, -1.0, 1.0) : 1.0;
}

MeshQuality mesh_quality(const Mesh& mesh)
{
  MeshQuality q;
  constexpr double to_deg = 180.0 / std::numbers::pi;
  std::vector<double> per_triangle_min;
  per_triangle_min.reserve(mesh.n_faces());
  q.min_angle_deg = 180;
  int obtuse = 0;
  for (auto f : mesh.faces()) {
    double tri_min = 180, tri_max = 0;
    for (const double radians : corner_angles(mesh, f)) {
      const double angle = radians * to_deg;
      tri_min = std::min(tri_min, angle);
      tri_max = std::max(tri_max, angle);
    }
    per_triangle_min.push_back(tri_min);
    q.min_angle_deg = std::min(q.min_angle_deg, tri_min);
    q.max_angle_deg = std::max(q.max_angle_deg, tri_max);
    obtuse += tri_max > 90.0;
  }
  if (!per_triangle_min.empty()) {
    const auto p05 = per_triangle_min.begin() + static_cast<long>(0.05 * (per_triangle_min.size() - 1));
    std::nth_element(per_triangle_min.begin(), p05, per_triangle_min.end());
    q.min_angle_p05_deg = *p05;
    q.obtuse_triangle_fraction = static_cast<double>(obtuse) / per_triangle_min.size();
  } else {
    q.min_angle_deg = 0;
  }

  double sum = 0, sum_sq = 0;
  q.edge_min = mesh.n_edges() ? std::numeric_limits<double>::infinity() : 0;
  for (auto e : mesh.edges()) {
    const double len = mesh.calc_edge_length(e);
    q.edge_min = std::min(q.edge_min, len);
    q.edge_max = std::max(q.edge_max, len);
    sum += len;
    sum_sq += len * len;
  }
  if (mesh.n_edges()) {
    q.edge_mean = sum / mesh.n_edges();
    q.edge_stddev = std::sqrt(std::max(0.0, sum_sq / mesh.n_edges() - q.edge_mean * q.edge_mean));
  }
  for (auto v : mesh.vertices())
    ++(mesh.is_boundary(v) ? q.boundary_valence_histogram : q.valence_histogram)[static_cast<int>(mesh.valence(v))];
  return q;
}

} // namespace sdflow
