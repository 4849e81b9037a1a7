//! The brute-force intersection check the shape and remeshing tests rely on, on adversarial pairs.
#include "support/exact_intersections.h"

#include <gtest/gtest.h>

namespace sdflow {
namespace {

using Points = VertexVectors;

std::size_t pairs_of(std::initializer_list<Eigen::Vector3d> points, std::initializer_list<std::array<int, 3>> faces)
{
  Points x(points.size(), 3);
  int i = 0;
  for (const auto& p : points)
    x.row(i++) = p.transpose();
  FaceIndices f(faces.size(), 3);
  i = 0;
  for (const auto& t : faces)
    f.row(i++) << t[0], t[1], t[2];
  // Built face by face so that non-manifold arrangements (crossing sheets) are allowed.
  Mesh mesh;
  for (Eigen::Index v = 0; v < x.rows(); ++v)
    mesh.add_vertex(to_point(x.row(v).transpose()));
  for (Eigen::Index t = 0; t < f.rows(); ++t)
    mesh.add_face(Mesh::VertexHandle(f(t, 0)), Mesh::VertexHandle(f(t, 1)), Mesh::VertexHandle(f(t, 2)));
  return analytic::brute_force_intersecting_pairs(mesh).size();
}

TEST(ExactIntersections, crossing_and_disjoint_triangles)
{
  // Two triangles piercing each other, then the second lifted clear.
  EXPECT_EQ(pairs_of({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, -1}, {0.5, 0.5, 1}, {3, 3, 0}}, {{0, 1, 2}, {3, 4, 5}}), 1u);
  EXPECT_EQ(pairs_of({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, 0.1}, {0.5, 0.5, 1}, {3, 3, 0.1}}, {{0, 1, 2}, {3, 4, 5}}), 0u);
  // Touching at a single point counts (closed triangles).
  EXPECT_EQ(pairs_of({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, 0}, {0.5, 0.5, 1}, {1, 2, 1}}, {{0, 1, 2}, {3, 4, 5}}), 1u);
}

TEST(ExactIntersections, shared_edges_count_only_when_folded_flat)
{
  // A fold of 90° along the shared edge: fine. Folded completely onto itself: overlap.
  EXPECT_EQ(pairs_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{0, 1, 2}, {1, 0, 3}}), 0u);
  EXPECT_EQ(pairs_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.3, 2, 0}}, {{0, 1, 2}, {1, 0, 3}}), 1u);
  // Coplanar, on opposite sides of the shared edge: a flat surface.
  EXPECT_EQ(pairs_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, -1, 0}}, {{0, 1, 2}, {1, 0, 3}}), 0u);
}

TEST(ExactIntersections, shared_vertices_count_only_when_they_meet_elsewhere)
{
  // A fan around a common vertex, not overlapping; then one blade turned through another.
  EXPECT_EQ(pairs_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}}, {{0, 1, 2}, {0, 3, 4}}), 0u);
  EXPECT_EQ(pairs_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, 0.5, -1}, {0.5, 0.5, 1}}, {{0, 1, 2}, {0, 3, 4}}), 1u);
  // Coplanar blades overlapping beyond the shared vertex.
  EXPECT_EQ(pairs_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 0.2, 0}, {0.2, 1, 0}}, {{0, 1, 2}, {0, 3, 4}}), 1u);
}

} // namespace
} // namespace sdflow
