//! mesh_statistics on a surface that crosses itself: the crossing is counted, TetGen is left out
//! where it would refuse, and the components that do not cross are still checked (issue 32).
#include "sdflow/check/statistics.h"
#include "sdflow/geometry/measures.h"
#include "support/analytic_meshes.h"
#include "support/mesh_checks.h"

#include <gtest/gtest.h>

namespace sdflow {
namespace {

//! An icosphere with one vertex pushed through its far side: one closed component that crosses
//! itself, as a repair without --remove-self-intersections can leave.
Mesh folded_sphere(const Eigen::Vector3d& centre)
{
  Mesh mesh = analytic::icosphere(2, 1.0, centre);
  auto v = *mesh.vertices().begin();
  const Mesh::Point c(centre.x(), centre.y(), centre.z());
  mesh.set_point(v, c - 1.5 * (mesh.point(v) - c));
  return mesh;
}

TEST(Statistics, crossing_component_is_counted_and_left_out_of_tetgen)
{
  const Mesh clean = analytic::icosphere(3, 2.0, Eigen::Vector3d(10, 0, 0));
  const Mesh mesh = analytic::disjoint_union(folded_sphere(Eigen::Vector3d::Zero()), clean);
  const MeshStatistics s = mesh_statistics(mesh);
  ASSERT_EQ(s.components.size(), 2u);
  EXPECT_GT(s.self_intersecting_pairs, 0);
  EXPECT_GT(s.components[0].crossing_faces, 0);
  EXPECT_FALSE(s.components[0].tetgen_volume.has_value());
  EXPECT_EQ(s.components[1].crossing_faces, 0);
  ASSERT_TRUE(s.components[1].tetgen_volume.has_value());
  EXPECT_NEAR(*s.components[1].tetgen_volume, enclosed_volume(clean), checks::kTetgenAgreement * enclosed_volume(clean));
  EXPECT_FALSE(s.tetgen_volume.has_value()) << "a total over some components is not the surface's";
  EXPECT_NE(s.tetgen_skipped.find("1 closed component"), std::string::npos) << s.tetgen_skipped;
}

TEST(Statistics, surface_that_does_not_cross_gets_every_tetgen_volume)
{
  const Mesh mesh = analytic::icosphere(3, 2.0);
  const MeshStatistics s = mesh_statistics(mesh);
  EXPECT_EQ(s.self_intersecting_pairs, 0);
  EXPECT_TRUE(s.tetgen_skipped.empty());
  ASSERT_TRUE(s.tetgen_volume.has_value());
  EXPECT_NEAR(*s.tetgen_volume, s.volume, checks::kTetgenAgreement * s.volume);
}

} // namespace
} // namespace sdflow
