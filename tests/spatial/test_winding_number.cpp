//! winding_number counts how many times the material is layered at a point: 1 inside a body, 0
//! outside, 2 where two bodies overlap, −1 inside a body turned inside out; round coordinates (a
//! cube's diagonals) do not make the ray miscount.
#include "support/analytic_meshes.h"

#include "sdflow/spatial/winding_number.h"

#include <gtest/gtest.h>

namespace sdflow {
namespace {

TEST(WindingNumber, is_one_inside_a_sphere_and_zero_outside)
{
  const Bvh tree(analytic::icosphere(3));
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.5, 0.2, -0.3), Eigen::Vector3d(-0.9, 0, 0)})
    EXPECT_EQ(winding_number(tree, p), 1) << p.transpose();
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(2, 0, 0), Eigen::Vector3d(0, 0, -1.5), Eigen::Vector3d(-3, 1, 1)})
    EXPECT_EQ(winding_number(tree, p), 0) << p.transpose();
}

TEST(WindingNumber, counts_overlapping_bodies_and_inside_out_ones)
{
  const Mesh a = analytic::icosphere(3);
  const Mesh b = analytic::icosphere(3, 1.0, Eigen::Vector3d(1, 0, 0));
  const Bvh both(analytic::disjoint_union(a, b));
  EXPECT_EQ(winding_number(both, Eigen::Vector3d(0.5, 0.1, 0)), 2);
  EXPECT_EQ(winding_number(both, Eigen::Vector3d(-0.7, 0, 0.1)), 1);
  EXPECT_EQ(winding_number(both, Eigen::Vector3d(2.5, 0, 0)), 0);

  const FaceIndices f = face_indices(a);
  FaceIndices flipped = f;
  flipped.col(1) = f.col(2);
  flipped.col(2) = f.col(1);
  EXPECT_EQ(winding_number(Bvh(make_mesh(vertex_positions(a), flipped)), Eigen::Vector3d(0.1, 0.2, 0.3)), -1);
}

TEST(WindingNumber, a_ray_along_a_cube_face_diagonal_counts_once)
{
  // From the centre along +x the ray meets the face x = 0.5 at its centre, on the diagonal
  // that splits it into two triangles.
  const Bvh tree(analytic::cube(1.0));
  EXPECT_EQ(winding_number(tree, Eigen::Vector3d(0, 0, 0)), 1);
  EXPECT_EQ(winding_number(tree, Eigen::Vector3d(-0.5, 0, 0) - Eigen::Vector3d(1e-3, 0, 0)), 0);
  EXPECT_EQ(winding_number(tree, Eigen::Vector3d(-1, 0.5, 0.5)), 0);
}

TEST(WindingNumber, an_empty_tree_winds_zero_times)
{
  EXPECT_EQ(winding_number(Bvh(), Eigen::Vector3d(0, 0, 0)), 0);
}

} // namespace
} // namespace sdflow
