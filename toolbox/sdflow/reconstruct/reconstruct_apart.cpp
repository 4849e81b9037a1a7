#include "sdflow/reconstruct/reconstruct_apart.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/topology.h"

#include <fmt/format.h>

#include <array>

namespace sdflow {
namespace {

//! The group of each of `count` rows (-1: none); InvalidParameter for a row out of range or in two.
std::vector<int> group_of_rows(const std::vector<std::vector<int>>& groups, int count, const char* caller)
{
  std::vector<int> group(static_cast<std::size_t>(count), -1);
  for (std::size_t g = 0; g < groups.size(); ++g)
    for (const int row : groups[g]) {
      if (row < 0 || row >= count)
        throw InvalidParameter(fmt::format("{}: group {} names point {}, outside [0, {})", caller, g, row, count));
      if (group[static_cast<std::size_t>(row)] >= 0)
        throw InvalidParameter(fmt::format("{}: point {} is in groups {} and {}", caller, row,
                                           group[static_cast<std::size_t>(row)], g));
      group[static_cast<std::size_t>(row)] = static_cast<int>(g);
    }
  return group;
}

} // namespace

Reconstruction reconstruct_apart(const VertexVectors& points, const VertexVectors& normals,
                                 const std::vector<std::vector<int>>& groups, const ReconstructionOptions& options)
{
  const auto n = static_cast<int>(points.rows());
  const std::vector<int> group = group_of_rows(groups, n, "reconstruct_apart");
  Reconstruction all;
  for (int i = 0; i < n; ++i)
    if (group[static_cast<std::size_t>(i)] < 0)
      all.unused.push_back(i);
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;
  for (const std::vector<int>& members : groups) {
    if (members.size() < 3) { // too few to make a triangle: left over, as the points of no group
      all.unused.insert(all.unused.end(), members.begin(), members.end());
      continue;
    }
    VertexVectors group_points(static_cast<Eigen::Index>(members.size()), 3), group_normals(group_points.rows(), 3);
    for (std::size_t m = 0; m < members.size(); ++m) {
      group_points.row(static_cast<Eigen::Index>(m)) = points.row(members[m]);
      group_normals.row(static_cast<Eigen::Index>(m)) = normals.row(members[m]);
    }
    const Reconstruction piece = reconstruct_surface(group_points, group_normals, options);
    const auto offset = static_cast<int>(vertices.size());
    for (const auto v : piece.mesh.vertices()) {
      vertices.push_back(to_eigen(piece.mesh.point(v)));
      all.source.push_back(members[static_cast<std::size_t>(piece.source[static_cast<std::size_t>(v.idx())])]);
    }
    for (const auto f : piece.mesh.faces()) {
      const auto c = triangle_corners(piece.mesh, f).index;
      triangles.push_back({offset + c[0], offset + c[1], offset + c[2]});
    }
    for (const int u : piece.unused)
      all.unused.push_back(members[static_cast<std::size_t>(u)]);
    all.components += piece.components;
  }
  all.mesh = make_mesh(point_rows(vertices), triangle_rows(triangles));
  return all;
}

bool joins_groups(const Reconstruction& rebuilt, const std::vector<std::vector<int>>& groups, int point_count)
{
  const std::vector<int> group = group_of_rows(groups, point_count, "joins_groups");
  int count = 0;
  const std::vector<int> component = face_component_ids(rebuilt.mesh, &count);
  std::vector<int> first_group(static_cast<std::size_t>(count), -1);
  for (const auto f : rebuilt.mesh.faces())
    for (const auto v : rebuilt.mesh.fv_range(f)) {
      const int row = rebuilt.source[static_cast<std::size_t>(v.idx())];
      if (row < 0 || row >= point_count)
        throw InvalidParameter(fmt::format("joins_groups: vertex {} comes from point {}, outside [0, {})", v.idx(), row,
                                           point_count));
      const int g = group[static_cast<std::size_t>(row)];
      int& seen = first_group[static_cast<std::size_t>(component[static_cast<std::size_t>(f.idx())])];
      if (g < 0)
        continue;
      if (seen >= 0 && seen != g)
        return true;
      seen = g;
    }
  return false;
}

} // namespace sdflow
