//! A contact line resampled by the re-triangulation (RetriangulationOptions::resample_boundary, as
//! flow/substrate_boundary.h asks): a rim whose edges a moving contact line stretched and shrank
//! comes back to edges near the target, its vertices exactly on the substrate's plane, with no
//! triangle lying flat on it; a kink is not kept as a corner; a kept rim (a fixed boundary) keeps
//! its vertices.
#include "sdflow/geometry/topology.h"
#include "sdflow/retri/pipeline.h"
#include "support/analytic_meshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace sdflow {
namespace {

//! A 90° cap of radius 1 on z = 0 whose contact line moved unevenly: its rim vertices are slid
//! along the circle toward one point (angle φ to φ³/π²), so that the rim's edges run from almost 0
//! to about 3 ℓ for ℓ = 2π/(rim vertices), and the ring above the rim is left where it was.
Mesh unevenly_stretched_cap()
{
  Mesh cap = analytic::spherical_cap(6, 1, 90);
  for (const auto v : cap.vertices()) {
    if (!cap.is_boundary(v))
      continue;
    auto p = cap.point(v);
    const double angle = std::atan2(p[1], p[0]);                 // in (−π, π]
    const double squeezed = angle * angle * angle / (std::numbers::pi * std::numbers::pi); // crowds them toward 0
    p[0] = std::cos(squeezed);
    p[1] = std::sin(squeezed);
    cap.set_point(v, p); // p[2] stays 0 exactly
  }
  return cap;
}

struct Rim {
  double shortest = 0, longest = 0;
  int vertices = 0;
  bool on_plane = true;
  int flat_triangles = 0; //!< faces with all three corners on the rim
};

Rim rim_of(const Mesh& mesh)
{
  Rim rim{.shortest = 1e300};
  for (const auto e : mesh.edges())
    if (mesh.is_boundary(e)) {
      rim.shortest = std::min(rim.shortest, static_cast<double>(mesh.calc_edge_length(e)));
      rim.longest = std::max(rim.longest, static_cast<double>(mesh.calc_edge_length(e)));
    }
  for (const auto v : mesh.vertices())
    if (mesh.is_boundary(v)) {
      ++rim.vertices;
      rim.on_plane &= mesh.point(v)[2] == 0.0;
    }
  for (const auto f : mesh.faces()) {
    int corners = 0;
    for (const auto v : mesh.fv_range(f))
      corners += mesh.is_boundary(v);
    rim.flat_triangles += corners == 3;
  }
  return rim;
}

TEST(ContactLineResampling, a_stretched_contact_line_comes_back_to_the_target_on_its_plane)
{
  const Mesh cap = unevenly_stretched_cap();
  const Rim before = rim_of(cap);
  const double ell = 2 * std::numbers::pi / before.vertices;
  ASSERT_LT(before.shortest, 0.1 * ell) << "the case no longer has the short edges it tests";
  ASSERT_GT(before.longest, 2 * ell) << "the case no longer has the long edges it tests";

  const RetriangulationResult kept = retriangulate(cap, {.edge_length = ell, .keep_boundary = true});
  EXPECT_EQ(rim_of(kept.mesh).shortest, before.shortest) << "a fixed rim keeps its vertices";

  const RetriangulationResult resampled =
      retriangulate(cap, {.edge_length = ell, .keep_boundary = true, .resample_boundary = true});
  const Rim after = rim_of(resampled.mesh);
  EXPECT_GT(after.shortest, 0.4 * ell);
  EXPECT_LT(after.longest, 2 * ell);
  EXPECT_TRUE(after.on_plane) << "every rim vertex exactly on z = 0";
  EXPECT_EQ(after.flat_triangles, 0);
  EXPECT_EQ(boundary_loops(resampled.mesh).size(), 1u);
  for (const auto v : resampled.mesh.vertices())
    EXPECT_GE(resampled.mesh.point(v)[2], 0.0);
}

//! The largest angle (degrees) by which a boundary loop of `mesh` turns at a vertex, in the plane.
double sharpest_turn(const Mesh& mesh)
{
  double sharpest = 0;
  for (const auto v : mesh.vertices()) {
    if (!mesh.is_boundary(v))
      continue;
    const auto out = mesh.halfedge_handle(v);
    const auto in = mesh.prev_halfedge_handle(out);
    const auto a = mesh.point(mesh.from_vertex_handle(in)), b = mesh.point(v), c = mesh.point(mesh.to_vertex_handle(out));
    const auto e = b - a, f = c - b;
    sharpest = std::max(sharpest, std::acos(std::clamp(static_cast<double>((e | f) / (e.norm() * f.norm())), -1.0, 1.0)) *
                                      180 / std::numbers::pi);
  }
  return sharpest;
}

TEST(ContactLineResampling, a_kink_of_the_contact_line_is_not_kept_as_a_corner)
{
  // One rim vertex of the cap pushed out in the plane, as a cut leaves the tip of a new contact
  // line: the rim turns there by far more than the remesher's corner angle (45°). A contact line
  // has no corners; kept as one, a tip whose film lies flat on the plane turned triangles over step
  // after step (an island of L/W = 12 at edge 0.1 crawled at τ ≈ 10⁻⁸ after its second break-up).
  Mesh cap = analytic::spherical_cap(6, 1, 90);
  const double ell = 2 * std::numbers::pi / rim_of(cap).vertices;
  for (const auto v : cap.vertices())
    if (cap.is_boundary(v) && cap.point(v)[0] > 0.999) {
      cap.set_point(v, cap.point(v) * 1.25);
      break;
    }
  ASSERT_GT(sharpest_turn(cap), 90) << "the case no longer has the kink it tests";
  const RetriangulationResult resampled =
      retriangulate(cap, {.edge_length = ell, .keep_boundary = true, .resample_boundary = true});
  EXPECT_LT(sharpest_turn(resampled.mesh), 90); // measured: 113.6° to 64.6°; kept as a corner, 113.6°
  EXPECT_TRUE(rim_of(resampled.mesh).on_plane);
}

} // namespace
} // namespace sdflow
