//! Components, Euler characteristic, genus and boundary loops.
#include "sdflow/geometry/topology.h"
#include "support/analytic_meshes.h"

#include <gtest/gtest.h>

namespace sdflow {
namespace {

TEST(Topology, genus_and_boundary_of_known_surfaces)
{
  struct Case {
    Mesh mesh;
    int genus, loops;
  };
  const std::vector<Case> cases = {{analytic::icosphere(2), 0, 0},
                                   {analytic::torus(20, 10, 6, 3), 1, 0},
                                   {analytic::conformal_torus(12, 6, 3), 1, 0},
                                   {analytic::disk(4), 0, 1}};
  for (const auto& c : cases) {
    SCOPED_TRACE(c.mesh.n_vertices());
    const auto topo = component_topology(c.mesh);
    ASSERT_EQ(topo.size(), 1u);
    EXPECT_EQ(topo[0].genus, c.genus);
    EXPECT_EQ(topo[0].boundary_loops, c.loops);
    EXPECT_EQ(topo[0].vertices, static_cast<int>(c.mesh.n_vertices()));
    EXPECT_EQ(topo[0].faces, static_cast<int>(c.mesh.n_faces()));
  }
}

TEST(Topology, annulus_has_two_boundary_loops)
{
  Mesh annulus = analytic::disk(6);
  for (auto f : annulus.faces())
    if (annulus.calc_face_centroid(f).norm() < 0.4)
      annulus.delete_face(f, true);
  annulus.garbage_collection();
  const auto topo = component_topology(annulus);
  ASSERT_EQ(topo.size(), 1u);
  EXPECT_EQ(topo[0].boundary_loops, 2);
  EXPECT_EQ(topo[0].euler_characteristic, 0);
  EXPECT_EQ(topo[0].genus, 0);
}

TEST(Topology, components_are_counted_separately)
{
  Mesh two = analytic::disjoint_union(analytic::torus(20, 10, 6, 3), analytic::icosphere(1, 1.0, Eigen::Vector3d(30, 0, 0)));
  int count = 0;
  const auto ids = face_component_ids(two, &count);
  EXPECT_EQ(count, 2);
  EXPECT_EQ(ids.front(), 0);
  EXPECT_EQ(ids.back(), 1);
  const auto topo = component_topology(two);
  ASSERT_EQ(topo.size(), 2u);
  EXPECT_EQ(topo[0].genus, 1);
  EXPECT_EQ(topo[1].genus, 0);
  EXPECT_EQ(topo[1].faces, 80);
}

} // namespace
} // namespace sdflow
