//! Creases (crease_edges.h) and the remesher that keeps them (remesh.h, crease_angle_deg): a box
//! keeps its edges and corners, its volume and its size, and remeshing it again changes nothing
//! much, where smoothing across its edges rounded it and refined it more at every round.
#include "sdflow/errors.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/remesh/crease_edges.h"
#include "sdflow/remesh/remesh.h"
#include "support/analytic_meshes.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <numbers>

namespace sdflow {
namespace {

using analytic::cube;
using analytic::icosphere;
using analytic::torus;

//! Whether p lies on an edge of the unit cube centred at the origin: two coordinates at ±½.
bool on_cube_edge(const Mesh::Point& p)
{
  int on_faces = 0;
  for (int i = 0; i < 3; ++i)
    on_faces += std::abs(std::abs(p[i]) - 0.5) < 1e-12;
  return on_faces >= 2;
}

//! The unit cube centred at the origin with every face an n × n grid of squares, each cut in two:
//! flat faces several triangles across, as a CAD part's faces are.
Mesh box_of_squares(int n)
{
  Mesh mesh;
  std::map<std::array<int, 3>, Mesh::VertexHandle> lattice;
  const auto vertex = [&](std::array<int, 3> ijk) {
    auto [it, inserted] = lattice.try_emplace(ijk);
    if (inserted)
      it->second = mesh.add_vertex(Mesh::Point(double(ijk[0]) / n - 0.5, double(ijk[1]) / n - 0.5, double(ijk[2]) / n - 0.5));
    return it->second;
  };
  for (int d = 0; d < 3; ++d)
    for (const int side : {0, n})
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          // (d, u, w) is right-handed, so (e_u, e_w) turns toward +e_d: outward on the side n.
          const int u = (d + 1) % 3, w = (d + 2) % 3;
          std::array<std::array<int, 3>, 4> corner{};
          for (int c = 0; c < 4; ++c) {
            corner[c][d] = side;
            corner[c][u] = i + (c == 1 || c == 2);
            corner[c][w] = j + (c >= 2);
          }
          auto q = std::array{vertex(corner[0]), vertex(corner[1]), vertex(corner[2]), vertex(corner[3])};
          if (side == 0)
            std::swap(q[1], q[3]);
          mesh.add_face(q[0], q[1], q[2]);
          mesh.add_face(q[0], q[2], q[3]);
        }
  return mesh;
}

double crease_length(const Mesh& mesh, const std::vector<int>& creases)
{
  double length = 0;
  for (const int e : creases)
    length += mesh.calc_edge_length(Mesh::EdgeHandle(e));
  return length;
}

//! The pipeline's stage-1 remeshing of `mesh` to ℓ with its curvature-adapted targets (4 edges per
//! radius of curvature, floor ℓ/4) and the curved projection.
Mesh remesh_as_the_pipeline_does(const Mesh& mesh, double ell, double crease_angle_deg)
{
  const std::vector<double> targets = radius_targets(mesh, {.edges_per_radius = 4, .min_length = ell / 4, .max_length = ell});
  return isotropic_remesh(mesh, {.edge_length = ell,
                                 .iterations = 3,
                                 .curved_projection = true,
                                 .crease_angle_deg = crease_angle_deg,
                                 .sizing = nearest_vertex_sizing(mesh, targets)})
      .mesh;
}

TEST(CreaseEdges, a_box_has_its_twelve_edges_and_a_sphere_or_a_thin_tube_none)
{
  const Mesh box = box_of_squares(4);
  ASSERT_NEAR(enclosed_volume(box), 1, 1e-12);
  const std::vector<int> box_edges = crease_edges(box, 45);
  EXPECT_EQ(box_edges.size(), 12u * 4);
  EXPECT_NEAR(crease_length(box, box_edges), 12, 1e-12);
  // Remeshed with its creases kept, the creases found are the box's edges, cut into pieces.
  const Mesh fine = isotropic_remesh(box, {.edge_length = 0.1, .iterations = 5, .crease_angle_deg = 45}).mesh;
  const std::vector<int> pieces = crease_edges(fine, 45);
  EXPECT_GT(pieces.size(), 12u * 7);
  EXPECT_NEAR(crease_length(fine, pieces), 12, 1e-9);
  for (const int e : pieces) {
    const auto h = fine.halfedge_handle(Mesh::EdgeHandle(e), 0);
    EXPECT_TRUE(on_cube_edge(fine.point(fine.from_vertex_handle(h))) && on_cube_edge(fine.point(fine.to_vertex_handle(h))));
  }
  // Two triangles a face: a square tube capped, whose edges no local test can tell from a coarse
  // cylinder's.
  EXPECT_TRUE(crease_edges(cube(), 45).empty());
  // A sphere turns by ~12° per edge, everywhere alike.
  EXPECT_TRUE(crease_edges(icosphere(3), 10).empty());
  // A remeshed tube 6 edges around (a neck about to pinch) turns by up to 60° at an edge, and as
  // much at the edges beside it: a curvature resolved by few edges, not a crease. (A tube of flat
  // quads, a prism, is creased: no local test tells it from a coarse cylinder.)
  const double major = 3, minor = 0.3;
  const PointProjection onto_tube = [major, minor](const Eigen::Vector3d& p) {
    const Eigen::Vector3d centre = major * Eigen::Vector3d(p.x(), p.y(), 0).normalized();
    return Eigen::Vector3d(centre + minor * (p - centre).normalized());
  };
  const Mesh tube = isotropic_remesh(torus(96, 12, major, minor),
                                     {.edge_length = 2 * std::numbers::pi * minor / 6, .iterations = 10, .project = onto_tube})
                        .mesh;
  EXPECT_TRUE(crease_edges(tube, 45).empty());
  EXPECT_THROW(crease_edges(box, 0), InvalidParameter);
  EXPECT_THROW(crease_edges(box, 180), InvalidParameter);
}

TEST(CreaseEdges, a_remeshed_box_keeps_its_corners_volume_and_area)
{
  const Mesh box = box_of_squares(4);
  const Mesh kept = isotropic_remesh(box, {.edge_length = 0.1, .iterations = 5, .curved_projection = true,
                                            .crease_angle_deg = 45})
                        .mesh;
  EXPECT_NEAR(enclosed_volume(kept), 1, 1e-12);
  EXPECT_NEAR(surface_area(kept), 6, 1e-12);
  int corners = 0;
  for (const auto v : kept.vertices()) {
    const auto p = kept.point(v);
    corners += std::abs(std::abs(p[0]) - 0.5) < 1e-15 && std::abs(std::abs(p[1]) - 0.5) < 1e-15 &&
               std::abs(std::abs(p[2]) - 0.5) < 1e-15;
  }
  EXPECT_EQ(corners, 8);
  // Without creases the remeshing cuts the box's edges and corners off.
  const Mesh rounded = isotropic_remesh(box, {.edge_length = 0.1, .iterations = 5, .curved_projection = true}).mesh;
  EXPECT_LT(enclosed_volume(rounded), 1 - 1e-3);
}

TEST(CreaseEdges, remeshing_a_box_again_and_again_is_a_fixed_point)
{
  // The run's re-triangulation remeshes the surface it made before, with targets measured on it.
  // Smoothed across, an edge of the box reads at every round as a curvature asking for edges 4
  // times shorter; kept, it reads as a crease (the target stays the local edge length).
  constexpr double ell = 0.1;
  Mesh mesh = remesh_as_the_pipeline_does(box_of_squares(4), ell, 45);
  const std::size_t first = mesh.n_faces();
  for (int round = 0; round < 3; ++round)
    mesh = remesh_as_the_pipeline_does(mesh, ell, 45);
  EXPECT_NEAR(static_cast<double>(mesh.n_faces()), static_cast<double>(first), 0.1 * first);
  EXPECT_NEAR(enclosed_volume(mesh), 1, 1e-12);
  EXPECT_NEAR(surface_area(mesh), 6, 1e-12);
}

TEST(CreaseEdges, the_remesher_refuses_a_crease_angle_out_of_range)
{
  EXPECT_THROW(isotropic_remesh(cube(), {.edge_length = 0.2, .crease_angle_deg = -1}), InvalidParameter);
  EXPECT_THROW(isotropic_remesh(cube(), {.edge_length = 0.2, .crease_angle_deg = 180}), InvalidParameter);
}

} // namespace
} // namespace sdflow
