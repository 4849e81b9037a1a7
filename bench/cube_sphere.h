#pragma once
//! \file cube_sphere.h
//! \brief Benchmark inputs: a closed sphere of 6n² + 2 vertices (the cube's faces gridded with the
//! equal-angle map and projected), n = 129 giving the 100k-vertex sphere of the figures,
//! and the same sphere with its top cap pushed down through the bottom (many real intersections).

#include "sdflow/mesh.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <random>
#include <tuple>

namespace sdflow::bench {

inline Mesh cube_sphere(int n, double radius = 1.0)
{
  std::map<std::tuple<int, int, int>, int> index;
  std::vector<Eigen::Vector3d> points;
  auto vertex = [&](int i, int j, int k) {
    auto [it, inserted] = index.try_emplace({i, j, k}, static_cast<int>(points.size()));
    if (inserted) {
      auto angle = [&](int c) { return std::tan(std::numbers::pi / 4 * (2.0 * c / n - 1.0)); };
      points.push_back(radius * Eigen::Vector3d(angle(i), angle(j), angle(k)).normalized());
    }
    return it->second;
  };
  std::vector<std::array<int, 3>> faces;
  for (int axis = 0; axis < 3; ++axis)
    for (int side : {0, n}) {
      // (u, v, axis) is a right-handed frame; on the low side the grid is walked mirrored so
      // that every triangle stays counter-clockwise seen from outside.
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      auto at = [&](int a, int b) {
        int c[3];
        c[axis] = side;
        c[u] = a;
        c[v] = side == n ? b : n - b;
        return vertex(c[0], c[1], c[2]);
      };
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
          const int p00 = at(a, b), p10 = at(a + 1, b), p11 = at(a + 1, b + 1), p01 = at(a, b + 1);
          faces.push_back({p00, p10, p11});
          faces.push_back({p00, p11, p01});
        }
    }
  VertexVectors x(points.size(), 3);
  for (std::size_t i = 0; i < points.size(); ++i)
    x.row(i) = points[i].transpose();
  sdflow::FaceIndices t(faces.size(), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    t.row(f) << faces[f][0], faces[f][1], faces[f][2];
  return make_mesh(x, t);
}

//! The sphere with every vertex above z = 0.2 reflected to 0.2 - 2.2 (z - 0.2): the cap passes
//! through the lower hemisphere.
inline Mesh pushed_through(Mesh mesh)
{
  for (auto v : mesh.vertices()) {
    auto p = mesh.point(v);
    if (p[2] > 0.2)
      p[2] = 0.2 - 2.2 * (p[2] - 0.2);
    mesh.set_point(v, p);
  }
  return mesh;
}

//! Positions moved along the outward normal by `amplitude` · (1 + ½ sin 3φ cos 2θ): a smooth
//! step like one of the flow (the sphere's normal is the position direction).
inline VertexVectors smooth_step(const Mesh& mesh, double amplitude)
{
  VertexVectors x = vertex_positions(mesh);
  for (Eigen::Index v = 0; v < x.rows(); ++v) {
    const Eigen::Vector3d p = x.row(v).transpose();
    const double phi = std::atan2(p.y(), p.x()), theta = std::acos(std::clamp(p.z() / p.norm(), -1.0, 1.0));
    x.row(v) += amplitude * (1 + 0.5 * std::sin(3 * phi) * std::cos(2 * theta)) * p.normalized().transpose();
  }
  return x;
}

//! Positions moved by independent normal noise of standard deviation `sigma`.
inline VertexVectors jiggled(const Mesh& mesh, double sigma, unsigned seed)
{
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  VertexVectors x = vertex_positions(mesh);
  for (Eigen::Index i = 0; i < x.size(); ++i)
    x.data()[i] += noise(rng);
  return x;
}

} // namespace sdflow::bench
