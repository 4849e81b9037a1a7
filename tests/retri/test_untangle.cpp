//! untangle_crossings undoes crossings by moving vertices only: a thin part whose walls passed
//! through each other is thickened back (outwards, not on through: the material is layered once
//! again), a fold is relaxed, the connectivity and the topology stay, and bodies that overlap are
//! left to the union.
#include "support/analytic_meshes.h"
#include "support/test_meshes.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/normals.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/retri/surface_repair.h"
#include "sdflow/retri/untangle.h"
#include "sdflow/spatial/intersect.h"
#include "sdflow/spatial/winding_number.h"

#include <gtest/gtest.h>

#include <cmath>

namespace sdflow {
namespace {

//! A sphere flattened to a pancake 0.4 thick whose middle (radius about 0.2) is pressed until the
//! top wall lies 0.1 below the bottom one: the walls of a thin part that passed through each other.
Mesh pressed_pancake()
{
  return test::mapped(analytic::icosphere(4), [](const Eigen::Vector3d& p) {
    const double r2 = p.x() * p.x() + p.y() * p.y();
    return Eigen::Vector3d(p.x(), p.y(), p.z() * (0.2 - 0.3 * std::exp(-r2 / 0.05)));
  });
}

//! Every vertex has material once just inside it and none just outside.
void expect_layered_once(const Mesh& mesh, double probe)
{
  const Bvh tree(mesh);
  const VertexVectors n = vertex_normals(mesh);
  const VertexVectors x = vertex_positions(mesh);
  int misplaced = 0;
  for (Eigen::Index v = 0; v < x.rows(); ++v) {
    const Eigen::Vector3d p = x.row(v).transpose(), normal = n.row(v).transpose();
    const int in = winding_number(tree, p - probe * normal), out = winding_number(tree, p + probe * normal);
    misplaced += in != 1 || out != 0;
    if (in != 1 || out != 0)
      ADD_FAILURE() << "vertex " << v << " at " << p.transpose() << ": winding " << in << " inside, " << out << " outside";
  }
  EXPECT_EQ(misplaced, 0);
}

TEST(Untangle, walls_that_passed_through_each_other_are_pushed_back_apart_with_the_topology_kept)
{
  const Mesh pressed = pressed_pancake();
  const UntangleResult r = untangle_crossings(pressed);
  ASSERT_GT(r.pairs_before, 0u);
  EXPECT_EQ(r.pairs_after, 0u);
  EXPECT_TRUE(self_intersections(r.mesh).empty());
  EXPECT_EQ(face_indices(r.mesh), face_indices(pressed));
  const TopologyCount before = count_topology(pressed), after = count_topology(r.mesh);
  EXPECT_EQ(after.components, before.components);
  EXPECT_EQ(after.genus, before.genus);
  EXPECT_GT(r.moved_vertices, 0u);
  EXPECT_LE(r.max_displacement, UntangleOptions{}.max_displacement + 1e-12);
  // Thickened back, not pushed on through: the walls are in their order again, at least the
  // clearance apart on the axis (within one move of it).
  const double unit = mean_edge_length(pressed);
  expect_layered_once(r.mesh, 0.01 * unit);
  const Mesh sphere = analytic::icosphere(4);
  double top = 1, bottom = -1; // the lowest point of the top wall and the highest of the bottom one
  for (const auto v : r.mesh.vertices()) {
    const Eigen::Vector3d p = to_eigen(r.mesh.point(v));
    if (p.x() * p.x() + p.y() * p.y() > 0.05 * 0.05)
      continue;
    if (sphere.point(v)[2] > 0)
      top = std::min(top, p.z());
    else
      bottom = std::max(bottom, p.z());
  }
  EXPECT_GT(top - bottom, (UntangleOptions{}.clearance - UntangleOptions{}.step) * unit);
}

TEST(Untangle, a_fold_is_relaxed_until_no_triangle_is_turned_over)
{
  // One vertex of a sphere dragged over the surface past its neighbours: its star folds over.
  Mesh folded = analytic::icosphere(3);
  const double unit = mean_edge_length(folded);
  const auto v = folded.vertex_handle(0);
  const Eigen::Vector3d p = to_eigen(folded.point(v));
  const Eigen::Vector3d tangent = p.unitOrthogonal();
  folded.set_point(v, to_point((p + 2.5 * unit * tangent).normalized()));
  ASSERT_FALSE(self_intersections(folded).empty());
  const UntangleResult r = untangle_crossings(folded);
  EXPECT_EQ(r.pairs_after, 0u);
  EXPECT_TRUE(self_intersections(r.mesh).empty());
  EXPECT_EQ(face_indices(r.mesh), face_indices(folded));
  EXPECT_LT(r.max_displacement, 2.5);
  expect_layered_once(r.mesh, 0.01 * unit);
}

TEST(Untangle, bodies_that_overlap_are_left_to_the_union)
{
  const Mesh two = analytic::disjoint_union(analytic::icosphere(3), analytic::icosphere(3, 1.0, Eigen::Vector3d(1, 0, 0)));
  ASSERT_FALSE(self_intersections(two).empty());
  const UntangleResult r = untangle_crossings(two);
  EXPECT_EQ(r.pairs_before, 0u);
  EXPECT_EQ(r.rounds, 0);
  EXPECT_EQ(vertex_positions(r.mesh), vertex_positions(two));
}

TEST(Untangle, options_out_of_range_are_refused)
{
  const Mesh sphere = analytic::icosphere(1);
  EXPECT_THROW(untangle_crossings(sphere, {.max_rounds = 0}), InvalidParameter);
  EXPECT_THROW(untangle_crossings(sphere, {.patience = 0}), InvalidParameter);
  EXPECT_THROW(untangle_crossings(sphere, {.step = 0}), InvalidParameter);
  EXPECT_THROW(untangle_crossings(sphere, {.step = 1.5}), InvalidParameter);
  EXPECT_THROW(untangle_crossings(sphere, {.max_displacement = 0}), InvalidParameter);
  EXPECT_THROW(untangle_crossings(sphere, {.clearance = -1}), InvalidParameter);
}

TEST(ResolveIntersections, a_pressed_thin_part_is_untangled_without_a_retriangulation)
{
  const Mesh pressed = pressed_pancake();
  const ResolveResult r = resolve_self_intersections(pressed);
  ASSERT_TRUE(r.untangled.has_value());
  EXPECT_EQ(r.untangled->pairs, r.pairs_before);
  EXPECT_TRUE(r.summaries.empty());
  EXPECT_EQ(r.pairs_after, 0u);
  EXPECT_EQ(r.mesh.n_faces(), pressed.n_faces());
}

} // namespace
} // namespace sdflow
