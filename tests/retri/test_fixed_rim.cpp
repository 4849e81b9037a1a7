//! The re-triangulation of a surface with a fixed boundary (retri/fixed_rim.h) and the orientation
//! of its open components (retri/open_orientation.h): the whole pipeline, its rebuild from points
//! forced or called for by a crossing, keeps the rim vertex for vertex, its loops and the surface's
//! orientation, and the volume restoration then gives the material volume back.
#include "sdflow/errors.h"
#include "sdflow/flow/volume.h"
#include "sdflow/geometry/material_volume.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/retri/fixed_rim.h"
#include "sdflow/retri/open_orientation.h"
#include "sdflow/retri/pipeline.h"
#include "sdflow/spatial/intersect.h"
#include "support/analytic_meshes.h"
#include "support/mesh_checks.h"
#include "support/test_meshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <cmath>
#include <numbers>
#include <vector>

namespace sdflow {
namespace {

using Profile = std::vector<Eigen::Vector2d>; // (ρ, z) from the axis outward

//! A surface of revolution with boundary: analytic::disk(rings) with the radius r in [0, 1] of each
//! vertex mapped to the point of `profile` at the fraction r of its length, turned by the
//! vertex's angle. A profile point with ρ < 0 lies across the axis.
Mesh revolved_disk(int rings, const Profile& profile)
{
  std::vector<double> arc{0};
  for (std::size_t i = 1; i < profile.size(); ++i)
    arc.push_back(arc.back() + (profile[i] - profile[i - 1]).norm());
  return test::mapped(analytic::disk(rings, 1.0), [&](const Eigen::Vector3d& p) {
    const double s = std::hypot(p.x(), p.y()) * arc.back(), angle = std::atan2(p.y(), p.x());
    const std::size_t i = std::min<std::size_t>(
        static_cast<std::size_t>(std::upper_bound(arc.begin(), arc.end(), s) - arc.begin()), arc.size() - 1);
    const double t = std::clamp((s - arc[i - 1]) / (arc[i] - arc[i - 1]), 0.0, 1.0);
    const Eigen::Vector2d q = (1 - t) * profile[i - 1] + t * profile[i];
    return Eigen::Vector3d(q.x() * std::cos(angle), q.x() * std::sin(angle), q.y());
  });
}

//! A unit sphere on a low mound of radius `mound` (rim at z = 0), joined to it by a neck that has
//! pinched through its axis: the neck's walls cross each other at two points on the axis, and the
//! wall between them is inside out (the threshold of a pinch-off, as the flow carries it). The
//! surface faces up, out of the material below it and inside the sphere. With `mound` = 0.6 the
//! surface ends where the neck meets the mound.
//! The inside-out wall is about 0.6 long and 0.35 across the axis.
Mesh sphere_pinching_off_a_mound(int rings, double mound = 4)
{
  const auto height = [mound](double rho) { return 0.3 * (1 - rho * rho / (mound * mound)); };
  Profile profile;
  const double last = std::numbers::pi - 0.5;
  for (int k = 0; k <= 40; ++k) {
    const double phi = last * k / 40;
    profile.emplace_back(std::sin(phi), 2.2 + std::cos(phi));
  }
  profile.emplace_back(-0.35, 1.0);
  profile.emplace_back(-0.35, 0.7);
  profile.emplace_back(0.6, height(0.6));
  for (int k = 1; k <= 40 && mound > 0.6; ++k) {
    const double rho = 0.6 + (mound - 0.6) * k / 40;
    profile.emplace_back(rho, height(rho));
  }
  return revolved_disk(rings, profile);
}

//! The boundary loops' vertex positions, each loop in the order of its halfedges.
std::vector<std::vector<Eigen::Vector3d>> rim_loops(const Mesh& mesh)
{
  std::vector<std::vector<Eigen::Vector3d>> loops;
  for (const auto& loop : boundary_loops(mesh)) {
    loops.emplace_back();
    for (const auto h : loop)
      loops.back().push_back(to_eigen(mesh.point(mesh.from_vertex_handle(h))));
  }
  return loops;
}

//! Whether `after` has the loops of `before`, each the same cyclic sequence of bit-identical
//! points run in the same direction (a surface turned over runs its loops the other way).
bool same_rims(const std::vector<std::vector<Eigen::Vector3d>>& before,
               const std::vector<std::vector<Eigen::Vector3d>>& after)
{
  if (before.size() != after.size())
    return false;
  for (const auto& loop : before) {
    bool found = false;
    for (const auto& other : after) {
      if (other.size() != loop.size())
        continue;
      const auto start = std::find(other.begin(), other.end(), loop.front());
      if (start == other.end())
        continue;
      const auto offset = static_cast<std::size_t>(start - other.begin());
      bool equal = true;
      for (std::size_t i = 0; i < loop.size() && equal; ++i)
        equal = loop[i] == other[(offset + i) % other.size()];
      found = found || equal;
    }
    if (!found)
      return false;
  }
  return true;
}

//! The open component's material volume (the mesh having exactly one open component).
double open_material_volume(const Mesh& mesh)
{
  const std::vector<double> volumes = material_volumes(mesh);
  const std::vector<ComponentTopology> topology = component_topology(mesh);
  double volume = std::numeric_limits<double>::quiet_NaN();
  int open = 0;
  for (std::size_t c = 0; c < topology.size(); ++c)
    if (!topology[c].closed()) {
      volume = volumes[c];
      ++open;
    }
  EXPECT_EQ(open, 1);
  return volume;
}

//! The volume restoration after the re-triangulation gives back the material volume and leaves
//! the rim where it is.
void expect_restored(const Mesh& before, Mesh after)
{
  const VolumeRestoration restored = restore_volumes_from(before, after);
  set_vertex_positions(after, restored.positions);
  EXPECT_NEAR(material_volume(after), material_volume(before), 1e-9 * std::abs(material_volume(before)));
  EXPECT_TRUE(same_rims(rim_loops(before), rim_loops(after)));
}

TEST(FixedRim, a_pinch_off_through_the_whole_pipeline_keeps_the_rim_bit_for_bit)
{
  const Mesh input = sphere_pinching_off_a_mound(40);
  ASSERT_FALSE(self_intersections(input).empty());
  ASSERT_GT(open_material_volume(input), 0);
  const RetriangulationResult r = retriangulate(input, {.edge_length = 0.2, .keep_boundary = true});
  EXPECT_TRUE(r.rim_kept);
  EXPECT_GT(r.removed_faces, 0);
  // The sphere pinched off: a closed body and the mound, whose one loop is the input's, vertex
  // for vertex and in the same direction.
  const std::vector<ComponentTopology> topology = component_topology(r.mesh);
  ASSERT_EQ(topology.size(), 2u);
  EXPECT_EQ(topology[0].boundary_loops + topology[1].boundary_loops, 1);
  EXPECT_TRUE(same_rims(rim_loops(input), rim_loops(r.mesh)));
  EXPECT_GT(open_material_volume(r.mesh), 0);
  EXPECT_EQ(r.turned_open_components, 0);
  // The body that pinched off is the sphere, not dropped as surface between the crossings.
  const std::vector<double> volumes = material_volumes(r.mesh);
  const std::size_t body = topology[0].closed() ? 0 : 1;
  EXPECT_GT(volumes[body], 0.8 * 4 * std::numbers::pi / 3);
  EXPECT_EQ(checks::self_intersecting_pairs(r.mesh), 0);
  EXPECT_TRUE(checks::is_two_manifold(r.mesh));
  expect_restored(input, r.mesh);
}

TEST(FixedRim, a_body_merged_into_a_plane_and_rebuilt_keeps_the_rim_bit_for_bit)
{
  // A unit sphere through a disk of radius 3 (z = 0) by 1.4: stage 0 joins them into the disk
  // with a spherical cap on it, and the rebuild from points is forced.
  const Mesh disk = analytic::disk(30, 3.0), ball = analytic::icosphere(3, 1.0, {0, 0, 0.4});
  const Mesh input = analytic::disjoint_union(disk, ball);
  const RetriangulationResult r =
      retriangulate(input, {.edge_length = 0.12, .keep_boundary = true, .always_rebuild = true});
  EXPECT_EQ(r.merged_components, 1);
  EXPECT_TRUE(r.rim_kept);
  const std::vector<ComponentTopology> topology = component_topology(r.mesh);
  ASSERT_EQ(topology.size(), 1u);
  EXPECT_EQ(topology[0].boundary_loops, 1);
  EXPECT_EQ(topology[0].genus, 0);
  EXPECT_TRUE(same_rims(rim_loops(disk), rim_loops(r.mesh)));
  // The cap above the plane, of height 1.4: π h² (3 − h) / 3.
  const double cap = std::numbers::pi * 1.4 * 1.4 * (3 - 1.4) / 3;
  EXPECT_NEAR(open_material_volume(r.mesh), cap, 0.03 * cap);
  EXPECT_EQ(checks::self_intersecting_pairs(r.mesh), 0);
  expect_restored(input, r.mesh);
}

TEST(FixedRim, a_crossing_in_the_band_along_the_rim_is_refused)
{
  // The sphere pinching off, its surface ending where the neck meets the mound: the lower crossing
  // is within a few rings of the rim, where the rim cannot be kept through the rebuild.
  const Mesh cut = sphere_pinching_off_a_mound(20, 0.6);
  const std::vector<FacePair> crossings = self_intersections(cut);
  ASSERT_FALSE(crossings.empty());
  ASSERT_FALSE(boundary_loops(cut).empty());
  EXPECT_THROW(rebuild_keeping_rim(cut, crossings, {.edge_length = 0.2}, 0.2, 1e9), InvalidMesh);
}

TEST(FixedRim, the_band_holds_the_faces_within_its_rings_of_the_rim)
{
  const Mesh disk = analytic::disk(10, 1.0); // rings of vertices 0.1 apart, the rim at r = 1
  const std::vector<char> band = rim_band(disk, 2);
  for (const auto f : disk.faces()) {
    double outermost = 0;
    for (const auto v : disk.fv_range(f))
      outermost = std::max(outermost, std::hypot(disk.point(v)[0], disk.point(v)[1]));
    // A face with a vertex on ring 9 or 10 (0 or 1 rings from the rim) is in the band, the others not.
    EXPECT_EQ(band[static_cast<std::size_t>(f.idx())] != 0, outermost > 0.85) << "face " << f.idx();
  }
  const std::vector<char> closed = rim_band(analytic::icosphere(2), 4);
  EXPECT_TRUE(std::none_of(closed.begin(), closed.end(), [](char b) { return b != 0; }));
}

TEST(OpenOrientation, an_open_surface_returned_turned_over_is_turned_back)
{
  // A mound (material below it, facing up) next to a sphere: turned over, the mound's material
  // volume changes sign; the check turns it back and leaves the sphere and every vertex alone.
  const Mesh mound = test::mapped(analytic::disk(12, 2.0), [](const Eigen::Vector3d& p) {
    return Eigen::Vector3d(p.x(), p.y(), 0.5 * (1 - p.squaredNorm() / 4));
  });
  const Mesh input = analytic::disjoint_union(mound, analytic::icosphere(2, 0.5, {5, 0, 0}));
  Mesh turned = input;
  {
    FaceIndices triangles = face_indices(input);
    for (Eigen::Index f = 0; f < static_cast<Eigen::Index>(mound.n_faces()); ++f)
      std::swap(triangles(f, 1), triangles(f, 2));
    turned = make_mesh(vertex_positions(input), triangles);
  }
  ASSERT_LT(material_volumes(turned)[0], 0);
  Mesh checked = turned;
  EXPECT_EQ(orient_open_components_like(input, checked), 1);
  EXPECT_EQ(vertex_positions(checked), vertex_positions(input));
  const std::vector<double> expected = material_volumes(input), got = material_volumes(checked);
  ASSERT_EQ(got.size(), expected.size());
  for (std::size_t c = 0; c < got.size(); ++c)
    EXPECT_NEAR(got[c], expected[c], 1e-12 * std::abs(expected[c]));
  Mesh unchanged = input;
  EXPECT_EQ(orient_open_components_like(input, unchanged), 0);
  EXPECT_EQ(face_indices(unchanged), face_indices(input));
}

TEST(OpenOrientation, the_whole_pipeline_returns_an_open_surface_as_it_faced)
{
  // A mound rebuilt from its points, rim free or fixed, faces up as it did: its material volume
  // keeps its sign and size.
  const Mesh mound = test::mapped(analytic::disk(20, 2.0), [](const Eigen::Vector3d& p) {
    return Eigen::Vector3d(p.x(), p.y(), 0.5 * (1 - p.squaredNorm() / 4));
  });
  const double volume = open_material_volume(mound);
  ASSERT_GT(volume, 0);
  for (const bool fixed : {false, true}) {
    const RetriangulationResult r =
        retriangulate(mound, {.edge_length = 0.12, .keep_boundary = fixed, .always_rebuild = true});
    EXPECT_TRUE(r.rebuilt);
    EXPECT_NEAR(open_material_volume(r.mesh), volume, 0.05 * volume) << (fixed ? "fixed rim" : "free rim");
  }
}

} // namespace
} // namespace sdflow
