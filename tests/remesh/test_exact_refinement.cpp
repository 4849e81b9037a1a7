//! Exact refinement (longest-edge bisection and coplanar Delaunay flips): the surface stays where it
//! was, point for point (a cube keeps its volume, faces and creases), edges end below the bound,
//! angles stay bounded below, topology and boundaries are kept.
#include "sdflow/errors.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/quality.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/remesh/exact_refinement.h"
#include "support/analytic_meshes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace sdflow {
namespace {

constexpr double kRounding = 1e-14; //!< midpoints are exact but for the rounding of coordinates
constexpr double kVolumeRounding = 1e-13; //!< relative: the volume sums a cone per triangle

double longest_edge(const Mesh& mesh)
{
  double longest = 0;
  for (const auto e : mesh.edges())
    longest = std::max(longest, mesh.calc_edge_length(e));
  return longest;
}

double smallest_angle(const Mesh& mesh)
{
  double smallest = 180;
  for (const auto f : mesh.faces())
    smallest = std::min(smallest, smallest_angle_deg(mesh, f));
  return smallest;
}

// Every triangle of the refined cube lies in one of the cube's face planes: no triangle cuts an edge
// or a corner, so the creases are exactly where they were; the volume and the area are those of the cube.
TEST(ExactRefinement, a_cube_keeps_its_faces_creases_and_volume)
{
  const Mesh cube = analytic::cube();
  const ExactRefinement r = refine_exactly(cube, {.max_edge_length = 0.2});
  EXPECT_GT(r.mesh.n_vertices(), 300u);
  EXPECT_LE(longest_edge(r.mesh), 0.2);
  EXPECT_NEAR(enclosed_volume(r.mesh), 1.0, kVolumeRounding);
  EXPECT_NEAR(surface_area(r.mesh), 6.0, kVolumeRounding);
  for (const auto f : r.mesh.faces()) {
    const TriangleCorners t = triangle_corners(r.mesh, f);
    bool in_a_face_plane = false;
    for (int axis = 0; axis < 3; ++axis)
      for (const double side : {-0.5, 0.5})
        in_a_face_plane |= std::abs(t.point[0][axis] - side) < kRounding && std::abs(t.point[1][axis] - side) < kRounding &&
                           std::abs(t.point[2][axis] - side) < kRounding;
    EXPECT_TRUE(in_a_face_plane) << "face " << f.idx();
  }
  for (int v = 0; v < 8; ++v) // the corners keep their indices and positions
    EXPECT_EQ(r.mesh.point(Mesh::VertexHandle(v)), cube.point(Mesh::VertexHandle(v)));
  const TopologyCount topology = count_topology(r.mesh);
  EXPECT_EQ(topology.components, 1);
  EXPECT_EQ(topology.genus, 0);
}

// Longest-edge bisection keeps angles above half the input's smallest (60° for these), and the
// flips in the faces' planes improve on that; the volume of each solid is kept to rounding.
TEST(ExactRefinement, equilateral_faces_stay_well_shaped_and_the_volume_is_kept)
{
  for (const Mesh& solid : {analytic::regular_tetrahedron(), analytic::regular_octahedron(), analytic::icosphere(0)}) {
    SCOPED_TRACE(solid.n_vertices());
    const double bound = mean_edge_length(solid) / 7;
    const ExactRefinement r = refine_exactly(solid, {.max_edge_length = bound});
    EXPECT_LE(longest_edge(r.mesh), bound);
    EXPECT_GE(smallest_angle(r.mesh), 30.0 - 1e-9);
    EXPECT_NEAR(enclosed_volume(r.mesh), enclosed_volume(solid), kVolumeRounding * enclosed_volume(solid));
    EXPECT_EQ(count_topology(r.mesh).genus, 0);
  }
}

// Two obtuse triangles in one plane share their long edge: it is flipped to the short diagonal,
// which lifts the smallest angle from 11° to 23°. Folded along that edge (a crease), they are not.
TEST(ExactRefinement, an_edge_in_a_plane_is_flipped_to_the_delaunay_diagonal_and_a_crease_is_not)
{
  VertexVectors x(4, 3);
  x << -1, 0, 0, 1, 0, 0, 0, 0.2, 0, 0, -0.2, 0;
  FaceIndices t(2, 3);
  t << 0, 1, 2, 1, 0, 3;
  const ExactRefinement flat = refine_exactly(make_mesh(x, t), {.max_edge_length = 10});
  EXPECT_EQ(flat.splits, 0);
  EXPECT_EQ(flat.flips, 1);
  EXPECT_GT(smallest_angle(flat.mesh), 22.0);
  EXPECT_NEAR(surface_area(flat.mesh), 0.4, kRounding);
  x(3, 2) = 0.1;
  const ExactRefinement folded = refine_exactly(make_mesh(x, t), {.max_edge_length = 10});
  EXPECT_EQ(folded.flips, 0);
}

// A boundary is split along itself: the disk keeps its rim polygon (its length) and its area.
TEST(ExactRefinement, an_open_surface_keeps_its_rim)
{
  const Mesh disk = analytic::disk(2);
  const ExactRefinement r = refine_exactly(disk, {.max_edge_length = mean_edge_length(disk) / 4});
  EXPECT_NEAR(surface_area(r.mesh), surface_area(disk), kVolumeRounding);
  ASSERT_EQ(boundary_loop_lengths(r.mesh).size(), 1u);
  EXPECT_NEAR(boundary_loop_lengths(r.mesh)[0], boundary_loop_lengths(disk)[0], kRounding);
}

TEST(ExactRefinement, stops_at_the_vertex_bound_and_refuses_a_bad_bound)
{
  const ExactRefinement r = refine_exactly(analytic::cube(), {.max_edge_length = 0.01, .max_vertices = 100});
  EXPECT_TRUE(r.stopped);
  EXPECT_EQ(r.mesh.n_vertices(), 100u);
  EXPECT_NEAR(enclosed_volume(r.mesh), 1.0, kVolumeRounding);
  EXPECT_THROW(refine_exactly(analytic::cube(), {.max_edge_length = 0}), InvalidParameter);
  EXPECT_THROW(refine_exactly(analytic::cube(), {.max_edge_length = INFINITY}), InvalidParameter);
}

} // namespace
} // namespace sdflow
