//! TetGen's tetrahedral volume against the divergence-theorem volume.
#include "sdflow/check/tetgen_volume.h"
#include "sdflow/errors.h"
#include "sdflow/geometry/measures.h"
#include "support/analytic_meshes.h"
#include "support/mesh_checks.h"

#include <gtest/gtest.h>

namespace sdflow {
namespace {

TEST(TetgenVolume, agrees_with_divergence_volume_on_closed_surfaces)
{
  for (const Mesh& mesh : {analytic::icosphere(3, 2.0), analytic::ellipsoid(3, 5, 4, 3),
                           analytic::conformal_torus(24, 6, 3), analytic::torus(30, 12, 4, 1)}) {
    SCOPED_TRACE(mesh.n_vertices());
    const auto checks = tetgen_volume_check(mesh);
    ASSERT_EQ(checks.size(), 1u);
    EXPECT_GT(checks[0].tetrahedra, 0);
    EXPECT_NEAR(checks[0].divergence_volume, enclosed_volume(mesh), 1e-12 * enclosed_volume(mesh));
    EXPECT_LT(checks[0].relative_difference(), checks::kTetgenAgreement);
  }
}

TEST(TetgenVolume, checks_each_closed_component_and_skips_open_ones)
{
  const Mesh spheres = analytic::disjoint_union(analytic::icosphere(2, 1.0), analytic::icosphere(2, 3.0, Eigen::Vector3d(10, 0, 0)));
  const Mesh with_disk = analytic::disjoint_union(spheres, analytic::disk(3));
  const auto checks = tetgen_volume_check(with_disk);
  ASSERT_EQ(checks.size(), 2u);
  EXPECT_EQ(checks[0].component, 0);
  EXPECT_EQ(checks[1].component, 1);
  EXPECT_LT(checks[1].relative_difference(), checks::kTetgenAgreement);
  EXPECT_GT(checks[1].tetgen_volume, 20 * checks[0].tetgen_volume);
}

TEST(TetgenVolume, self_intersecting_surface_is_rejected_with_a_reason)
{
  Mesh mesh = analytic::icosphere(2);
  // Push one vertex through the far side of the sphere.
  auto v = *mesh.vertices().begin();
  mesh.set_point(v, -1.5 * mesh.point(v));
  try {
    tetgen_volume_check(mesh);
    FAIL() << "expected InvalidMesh";
  } catch (const InvalidMesh& e) {
    EXPECT_NE(std::string(e.what()).find("component 0"), std::string::npos) << e.what();
  }
}

// Issue 13, defects 1 and 2: what crashed or aborted TetGen is refused before it with a reason.
TEST(TetgenVolume, far_away_vertex_and_flat_body_are_refused_before_tetgen)
{
  Mesh far = analytic::icosphere(2);
  far.set_point(*far.vertices().begin(), Mesh::Point(2e9, 0, 0));
  try {
    tetgen_volume_check(far);
    FAIL() << "expected InvalidMesh";
  } catch (const InvalidMesh& e) {
    EXPECT_NE(std::string(e.what()).find("--no-tetgen"), std::string::npos) << e.what();
  }
  Mesh flat = analytic::icosphere(2);
  for (auto v : flat.vertices())
    flat.point(v)[2] = 0;
  try {
    tetgen_volume_check(flat);
    FAIL() << "expected InvalidMesh";
  } catch (const InvalidMesh& e) {
    EXPECT_NE(std::string(e.what()).find("encloses no volume"), std::string::npos) << e.what();
  }
}

// Issue 13, defect 4: a cavity's TetGen volume is negative like its divergence volume.
TEST(TetgenVolume, cavity_volume_carries_the_sign_of_the_divergence_volume)
{
  const Mesh sphere = analytic::icosphere(2);
  FaceIndices faces = face_indices(sphere);
  faces.col(1).swap(faces.col(2));
  const Mesh inverted = make_mesh(vertex_positions(sphere), faces);
  const auto checks = tetgen_volume_check(inverted);
  ASSERT_EQ(checks.size(), 1u);
  EXPECT_LT(checks[0].divergence_volume, 0);
  EXPECT_LT(checks[0].tetgen_volume, 0);
  EXPECT_LT(checks[0].relative_difference(), checks::kTetgenAgreement);
}

} // namespace
} // namespace sdflow
