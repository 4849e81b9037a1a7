//! Volume restoration (volume.h).
#include "sdflow/errors.h"
#include "sdflow/flow/volume.h"
#include "sdflow/geometry/measures.h"
#include "support/analytic_meshes.h"

#include <gtest/gtest.h>

namespace sdflow {
namespace {

constexpr double round_off_volume = 1e-13; // relative

TEST(RestoreVolumes, each_closed_component_gets_its_target_volume_back)
{
  // Two components: an ellipsoid and a torus far away; targets 3% off their volumes.
  const Mesh a = analytic::ellipsoid(3, 5, 4, 3);
  Mesh b = analytic::torus(32, 16, 3, 1);
  for (auto v : b.vertices())
    b.set_point(v, b.point(v) + Mesh::Point(20, 0, 0));
  VertexVectors positions(a.n_vertices() + b.n_vertices(), 3);
  positions << vertex_positions(a), vertex_positions(b);
  Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor> triangles(a.n_faces() + b.n_faces(), 3);
  triangles << face_indices(a), face_indices(b).array() + static_cast<int>(a.n_vertices());
  Mesh both = make_mesh(positions, triangles);

  std::vector<double> targets = component_volumes(both);
  ASSERT_EQ(targets.size(), 2u);
  targets[0] *= 1.03;
  targets[1] *= 0.97;
  const VolumeRestoration r = restore_volumes(both, targets);
  set_vertex_positions(both, r.positions);
  const std::vector<double> after = component_volumes(both);
  for (int k = 0; k < 2; ++k) {
    SCOPED_TRACE(k);
    EXPECT_NEAR(after[k], targets[k], round_off_volume * targets[k]);
  }
  EXPECT_GT(r.offsets[0], 0);
  EXPECT_LT(r.offsets[1], 0);
  EXPECT_LT(r.max_relative_error, round_off_volume);
}

TEST(RestoreVolumes, open_components_are_left_alone)
{
  const Mesh disk = analytic::disk(4);
  const VolumeRestoration r = restore_volumes(disk, {1.0});
  EXPECT_EQ(r.positions, vertex_positions(disk));
  EXPECT_THROW(restore_volumes(disk, {}), InvalidParameter);
}

} // namespace
} // namespace sdflow
