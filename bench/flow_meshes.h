#pragma once
//! \file flow_meshes.h
//! \brief Benchmark surfaces of any size: geodesic spheres (icosahedron, every face cut into k²
//! triangles, 10k² + 2 vertices), so 10k, 100k and 400k vertices are k = 32, 100, 200.

#include "sdflow/mesh.h"

#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

namespace sdflow::bench {

//! Unit geodesic sphere of frequency k, outward oriented, radii r(p) = 1 + amplitude P2(z).
inline Mesh geodesic_sphere(int k, double amplitude = 0.0)
{
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  const std::array<Eigen::Vector3d, 12> corner{{{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                                                {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                                                {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}}};
  const std::array<std::array<int, 3>, 20> faces{{{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11},
                                                  {1, 5, 9}, {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                                  {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8}, {3, 8, 9},
                                                  {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}}};
  std::vector<Eigen::Vector3d> points(corner.begin(), corner.end());
  std::map<std::pair<int, int>, int> edge_start; // first id of an edge's interior points, from min to max
  auto edge_point = [&](int u, int v, int step) { // step-th point from u toward v, 1..k-1
    const auto key = std::minmax(u, v);
    auto [it, inserted] = edge_start.try_emplace({key.first, key.second}, static_cast<int>(points.size()));
    if (inserted)
      for (int s = 1; s < k; ++s)
        points.push_back(corner[key.first] + (corner[key.second] - corner[key.first]) * s / k);
    return it->second + (u == key.first ? step : k - step) - 1;
  };
  std::vector<std::array<int, 3>> triangles;
  for (const auto& f : faces) {
    std::vector<std::vector<int>> id(k + 1, std::vector<int>(k + 1, -1));
    for (int i = 0; i <= k; ++i)
      for (int j = 0; i + j <= k; ++j) {
        const int l = k - i - j; // barycentric (l, i, j) on (a, b, c)
        if (i == 0 && j == 0) id[i][j] = f[0];
        else if (l == 0 && j == 0) id[i][j] = f[1];
        else if (l == 0 && i == 0) id[i][j] = f[2];
        else if (j == 0) id[i][j] = edge_point(f[0], f[1], i);
        else if (i == 0) id[i][j] = edge_point(f[0], f[2], j);
        else if (l == 0) id[i][j] = edge_point(f[1], f[2], j);
        else {
          id[i][j] = static_cast<int>(points.size());
          points.push_back((corner[f[0]] * l + corner[f[1]] * i + corner[f[2]] * j) / k);
        }
      }
    for (int i = 0; i < k; ++i)
      for (int j = 0; i + j < k; ++j) {
        triangles.push_back({id[i][j], id[i + 1][j], id[i][j + 1]});
        if (i + j + 1 < k)
          triangles.push_back({id[i + 1][j], id[i + 1][j + 1], id[i][j + 1]});
      }
  }
  VertexVectors positions(points.size(), 3);
  for (std::size_t v = 0; v < points.size(); ++v) {
    const Eigen::Vector3d u = points[v].normalized();
    const double radius = 1.0 + amplitude * 0.5 * (3 * u.z() * u.z() - 1);
    positions.row(v) = (radius * u).transpose();
  }
  sdflow::FaceIndices tri(triangles.size(), 3);
  for (std::size_t f = 0; f < triangles.size(); ++f)
    tri.row(f) << triangles[f][0], triangles[f][1], triangles[f][2];
  return make_mesh(positions, tri);
}

} // namespace sdflow::bench
