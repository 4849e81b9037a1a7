//! The floor of a remeshing's targets beside a kept boundary (remesh/kept_boundary_sizing.h): the
//! boundary's own edge length at the boundary, nothing one edge length away, and nothing on a
//! closed surface.
#include "sdflow/errors.h"
#include "sdflow/remesh/kept_boundary_sizing.h"
#include "support/analytic_meshes.h"

#include <gtest/gtest.h>

#include <vector>

namespace sdflow {
namespace {

constexpr double kTinyTarget = 1e-3;

//! The mean length of v's two boundary edges.
double boundary_edge_length_at(const Mesh& mesh, Mesh::VertexHandle v)
{
  double length = 0;
  int edges = 0;
  for (const auto h : mesh.voh_range(v))
    if (mesh.is_boundary(mesh.edge_handle(h))) {
      length += mesh.calc_edge_length(h);
      ++edges;
    }
  return length / edges;
}

TEST(KeptBoundarySizing, the_floor_is_the_boundary_edge_at_the_boundary_and_fades_within_one_edge)
{
  const Mesh disk = analytic::disk(8); // unit disk, 8 rings
  std::vector<double> targets(disk.n_vertices(), kTinyTarget);
  floor_targets_beside_kept_boundary(disk, targets);
  double rim_edge = 0;
  for (const auto v : disk.vertices())
    if (disk.is_boundary(v)) {
      EXPECT_DOUBLE_EQ(targets[v.idx()], boundary_edge_length_at(disk, v));
      rim_edge = std::max(rim_edge, boundary_edge_length_at(disk, v));
    }
  ASSERT_GT(rim_edge, 0);
  for (const auto v : disk.vertices()) {
    const double from_rim = 1 - disk.point(v).norm();
    SCOPED_TRACE(from_rim);
    if (from_rim >= rim_edge) {
      EXPECT_EQ(targets[v.idx()], kTinyTarget); // beyond one edge: untouched
    } else if (!disk.is_boundary(v)) {
      EXPECT_LE(targets[v.idx()], rim_edge - from_rim + 1e-12); // fading with the distance
    }
  }
  // Larger targets stay as they are: it is a floor.
  std::vector<double> large(disk.n_vertices(), 10.0);
  floor_targets_beside_kept_boundary(disk, large);
  EXPECT_EQ(large, std::vector<double>(disk.n_vertices(), 10.0));
}

TEST(KeptBoundarySizing, a_closed_surface_keeps_its_targets_and_a_wrong_count_is_refused)
{
  const Mesh sphere = analytic::icosphere(2);
  std::vector<double> targets(sphere.n_vertices(), kTinyTarget);
  floor_targets_beside_kept_boundary(sphere, targets);
  EXPECT_EQ(targets, std::vector<double>(sphere.n_vertices(), kTinyTarget));
  std::vector<double> too_few(3, kTinyTarget);
  EXPECT_THROW(floor_targets_beside_kept_boundary(sphere, too_few), InvalidParameter);
}

} // namespace
} // namespace sdflow
