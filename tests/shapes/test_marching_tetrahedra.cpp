//! Marching tetrahedra on the octree, and clipping along a second level set.
#include "sdflow/errors.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/shapes/catalogue.h"
#include "sdflow/shapes/marching_tetrahedra.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace sdflow {
namespace {

bool has_boundary(const Mesh& mesh)
{
  for (auto h : mesh.halfedges())
    if (h.is_boundary())
      return true;
  return false;
}

TEST(MarchingTetrahedra, sphere_is_closed_outward_and_near_the_surface)
{
  const auto sphere = sphere_shape({.radius = 2});
  const double cell = 0.25;
  const Mesh mesh = marching_tetrahedra(sphere, {.cell_size = cell});
  const auto components = component_topology(mesh);
  ASSERT_EQ(components.size(), 1u);
  EXPECT_TRUE(components[0].closed());
  EXPECT_EQ(components[0].genus, 0);
  const double exact = 4 * std::numbers::pi * 8 / 3;
  EXPECT_NEAR(enclosed_volume(mesh), exact, 0.05 * exact); // positive: facing outward
  for (auto v : mesh.vertices())
    EXPECT_LE(std::abs(sphere.value(to_eigen(mesh.point(v)))), cell);
}

TEST(MarchingTetrahedra, refined_octree_has_no_cracks)
{
  // The sintering cluster's necks and slots refine the octree; transition cells must conform,
  // or the surface would have boundary edges.
  const auto cluster = sintering_cluster_shape();
  const Mesh coarse = marching_tetrahedra(cluster, {.cell_size = 0.6, .detail_levels = 0});
  const Mesh refined = marching_tetrahedra(cluster, {.cell_size = 0.6, .detail_levels = 2});
  EXPECT_GT(refined.n_vertices(), coarse.n_vertices()); // refinement happened
  for (const Mesh* mesh : {&coarse, &refined}) {
    EXPECT_FALSE(has_boundary(*mesh));
    const auto components = component_topology(*mesh);
    ASSERT_EQ(components.size(), 1u);
    EXPECT_EQ(components[0].genus, 5);
  }
}

TEST(MarchingTetrahedra, thin_tubes_are_resolved_by_detail_levels)
{
  // A neck of radius 0.15 in cells of 0.6: only refinement keeps the dumbbell in one piece.
  const auto dumbbell = dumbbell_shape({.neck_width = 0.3});
  const Mesh mesh = marching_tetrahedra(dumbbell, {.cell_size = 0.6, .detail_levels = 3});
  const auto components = component_topology(mesh);
  ASSERT_EQ(components.size(), 1u);
  EXPECT_EQ(components[0].genus, 0);
  EXPECT_TRUE(components[0].closed());
}

TEST(MarchingTetrahedra, clipping_cuts_a_plane_to_a_disk)
{
  const auto scene = spheres_on_plane_shape({.disk_radius = 9});
  const double cell = scene.feature_size / 2; // what the mesher uses: resolves the central hole
  const Mesh plane = marching_tetrahedra(scene, {.cell_size = cell});
  EXPECT_TRUE(has_boundary(plane)); // the plane leaves the box
  const Mesh disk = clip_mesh(plane, scene.clip);
  const auto components = component_topology(disk);
  ASSERT_EQ(components.size(), 1u);
  EXPECT_EQ(components[0].boundary_loops, 1);
  EXPECT_EQ(components[0].genus, 3);
  for (auto v : disk.vertices()) {
    const Eigen::Vector3d p = to_eigen(disk.point(v));
    // Cut points sit at the linear zero of g on an edge, nudged at most 1e-3 of the edge
    // inward from its ends; g is convex, so they are inside up to that nudge.
    EXPECT_LE(scene.clip(p), 1e-3 * cell);
    if (disk.is_boundary(v)) {
      EXPECT_NEAR(scene.clip(p), 0, 0.05 * cell);
    }
  }
}

TEST(MarchingTetrahedra, refuses_bad_options)
{
  const auto sphere = sphere_shape();
  EXPECT_THROW(marching_tetrahedra(sphere, {.cell_size = 0}), InvalidParameter);
  EXPECT_THROW(marching_tetrahedra(sphere, {.cell_size = 0.1, .detail_levels = -1}), InvalidParameter);
  EXPECT_THROW(marching_tetrahedra(sphere, {.cell_size = 1e-7}), InvalidParameter); // lattice too fine
}

} // namespace
} // namespace sdflow
