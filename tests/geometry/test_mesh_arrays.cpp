#include "sdflow/mesh.h"
#include "support/analytic_meshes.h"

#include <gtest/gtest.h>

namespace sdflow {
namespace {

//! collect_garbage drops deleted elements as garbage_collection does, and leaves a mesh without any
//! exactly as it was (the same handles, corners and points).
TEST(CollectGarbage, drops_deleted_elements_and_leaves_a_clean_mesh_as_it_was)
{
  const Mesh sphere = analytic::icosphere(3);
  Mesh clean = sphere;
  collect_garbage(clean);
  EXPECT_EQ(face_indices(clean), face_indices(sphere));
  EXPECT_EQ(vertex_positions(clean), vertex_positions(sphere));
  for (auto h : sphere.halfedges())
    EXPECT_EQ(clean.next_halfedge_handle(h), sphere.next_halfedge_handle(h));

  Mesh edited = sphere;
  edited.delete_face(Mesh::FaceHandle(5), true);
  Mesh expected = edited;
  expected.garbage_collection();
  collect_garbage(edited);
  EXPECT_EQ(edited.n_faces(), sphere.n_faces() - 1);
  EXPECT_EQ(face_indices(edited), face_indices(expected));
  EXPECT_EQ(vertex_positions(edited), vertex_positions(expected));
}

} // namespace
} // namespace sdflow
