//! Appendix B: the union of two intersecting closed surfaces.
#include "sdflow/check/tetgen_volume.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/retri/surface_union.h"
#include "sdflow/spatial/intersect.h"
#include "support/analytic_meshes.h"

#include <gtest/gtest.h>

#include <numbers>

namespace sdflow {
namespace {

constexpr double pi = std::numbers::pi;

//! Volume of the union of two balls of radius r whose centres are d apart (d < 2r).
double two_ball_union_volume(double r, double d)
{
  const double lens = pi * (4 * r + d) * (2 * r - d) * (2 * r - d) / 12;
  return 2 * 4.0 / 3 * pi * r * r * r - lens;
}

TEST(SurfaceUnion, two_overlapping_spheres_give_one_closed_sphere_like_surface)
{
  for (double d : {1.0, 1.5}) {
    SCOPED_TRACE(d);
    const Mesh a = analytic::icosphere(4, 1.0), b = analytic::icosphere(4, 1.0, Eigen::Vector3d(d, 0.1, 0.05));
    const UnionResult u = surface_union(a, b);
    const auto topo = component_topology(u.mesh);
    ASSERT_EQ(topo.size(), 1u);
    EXPECT_TRUE(topo[0].closed());
    EXPECT_EQ(topo[0].genus, 0);
    EXPECT_EQ(u.joined_loops, 1);
    EXPECT_TRUE(self_intersections(u.mesh).empty());
    // The meshes are inscribed polyhedra, so compare with the union of the two input polyhedra's
    // volumes scaled as the sphere's: a 1% band covers discretisation and the zipper strip.
    const double expected = two_ball_union_volume(1.0, std::hypot(d, 0.1, 0.05)) * enclosed_volume(a) / (4.0 / 3 * pi);
    EXPECT_NEAR(enclosed_volume(u.mesh), expected, 0.01 * expected);
    const auto checks = tetgen_volume_check(u.mesh);
    ASSERT_EQ(checks.size(), 1u);
    EXPECT_LT(checks[0].relative_difference(), 1e-9);
  }
}

TEST(SurfaceUnion, sphere_resting_on_a_torus_tube_joins_along_one_loop_and_keeps_genus_one)
{
  const Mesh torus = analytic::conformal_torus(48, 2.0, 0.7);
  const Mesh sphere = analytic::icosphere(4, 0.9, Eigen::Vector3d(2.0, 0.05, 0.8));
  const UnionResult u = surface_union(torus, sphere);
  const auto topo = component_topology(u.mesh);
  ASSERT_EQ(topo.size(), 1u);
  EXPECT_TRUE(topo[0].closed());
  EXPECT_EQ(topo[0].genus, 1);
  EXPECT_EQ(u.joined_loops, 1);
  EXPECT_TRUE(self_intersections(u.mesh).empty());
  EXPECT_GT(enclosed_volume(u.mesh), enclosed_volume(torus));
}

TEST(SurfaceUnion, disjoint_surfaces_stay_separate_and_nested_ones_keep_the_outer)
{
  const Mesh a = analytic::icosphere(2, 1.0), far = analytic::icosphere(2, 1.0, Eigen::Vector3d(5, 0, 0));
  const UnionResult apart = surface_union(a, far);
  EXPECT_EQ(component_topology(apart.mesh).size(), 2u);
  EXPECT_EQ(apart.removed_faces_a + apart.removed_faces_b, 0);

  const Mesh inner = analytic::icosphere(2, 0.3, Eigen::Vector3d(0.1, 0, 0));
  const UnionResult nested = surface_union(a, inner);
  EXPECT_EQ(component_topology(nested.mesh).size(), 1u);
  EXPECT_EQ(nested.removed_faces_b, static_cast<int>(inner.n_faces()));
  EXPECT_NEAR(enclosed_volume(nested.mesh), enclosed_volume(a), 1e-12);
}

} // namespace
} // namespace sdflow
