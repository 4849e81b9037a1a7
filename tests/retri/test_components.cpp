//! Splitting into connected components and keeping the large ones.
#include "sdflow/errors.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/retri/components.h"
#include "support/analytic_meshes.h"
#include "support/test_meshes.h"

#include <gtest/gtest.h>

namespace sdflow {
namespace {

//! A torus (400 faces), an icosphere (320), a small icosphere (80) and a lone triangle (1),
//! deliberately not in size order.
Mesh several_bodies()
{
  const Mesh sphere = analytic::icosphere(2, 1.0, Eigen::Vector3d(10, 0, 0));
  const Mesh torus = analytic::torus(20, 10, 3, 1);
  const Mesh small = analytic::icosphere(1, 0.5, Eigen::Vector3d(-10, 0, 0));
  VertexVectors x(3, 3);
  x << 0, 20, 0, 1, 20, 0, 0, 21, 0;
  FaceIndices t(1, 3);
  t << 0, 1, 2;
  const Mesh triangle = make_mesh(x, t);
  return test::disjoint_union({&sphere, &triangle, &torus, &small});
}

void expect_no_isolated_vertex(const Mesh& mesh)
{
  for (auto v : mesh.vertices())
    EXPECT_FALSE(mesh.is_isolated(v));
}

TEST(Components, split_gives_every_body_largest_first_with_its_topology)
{
  const auto parts = split_components(several_bodies());
  ASSERT_EQ(parts.size(), 4u);
  const std::vector<int> faces = {400, 320, 80, 1};
  const std::vector<int> genus = {1, 0, 0, 0};
  for (std::size_t i = 0; i < parts.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(static_cast<int>(parts[i].n_faces()), faces[i]);
    const auto topo = component_topology(parts[i]);
    ASSERT_EQ(topo.size(), 1u);
    EXPECT_EQ(topo[0].genus, genus[i]);
    EXPECT_EQ(topo[0].vertices, static_cast<int>(parts[i].n_vertices()));
    expect_no_isolated_vertex(parts[i]);
  }
  EXPECT_EQ(component_topology(parts[3])[0].boundary_loops, 1);
}

TEST(Components, keep_by_size_and_by_rank)
{
  const Mesh mesh = several_bodies();
  const ComponentSelection large = keep_components(mesh, {.min_faces = 50});
  EXPECT_EQ(large.mesh.n_faces(), 800u);
  EXPECT_EQ(large.kept.size(), 3u);
  EXPECT_EQ(large.dropped.size(), 1u);
  EXPECT_EQ(large.faces[large.dropped[0]], 1);
  expect_no_isolated_vertex(large.mesh);

  const ComponentSelection two = keep_components(mesh, {.keep_largest = 2});
  EXPECT_EQ(two.mesh.n_faces(), 720u);
  EXPECT_EQ(two.faces[two.kept[0]], 400);
  EXPECT_EQ(two.faces[two.kept[1]], 320);
  int count = 0;
  face_component_ids(two.mesh, &count);
  EXPECT_EQ(count, 2);

  const ComponentSelection both = keep_components(mesh, {.min_faces = 350, .keep_largest = 3});
  EXPECT_EQ(both.mesh.n_faces(), 400u);

  const ComponentSelection all = keep_components(mesh);
  EXPECT_EQ(all.mesh.n_faces(), mesh.n_faces());
  EXPECT_EQ(all.mesh.n_vertices(), mesh.n_vertices());
  EXPECT_TRUE(all.dropped.empty());

  EXPECT_TRUE(split_components(mesh, {.min_faces = 1000}).empty());
  EXPECT_THROW(keep_components(mesh, {.min_faces = 0}), InvalidParameter);
  EXPECT_THROW(split_components(mesh, {.keep_largest = -1}), InvalidParameter);
}

TEST(Components, bodies_touching_at_a_vertex_are_separate_and_split_cleanly)
{
  // Two fans meeting only at vertex 0: two components through edges, one pinched vertex.
  VertexVectors x(7, 3);
  x << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, -1, 0, 0.5, -1, -1, 0.5, 0, -1, 0.5;
  FaceIndices t(4, 3);
  t << 0, 1, 2, 0, 2, 3, 0, 4, 5, 0, 5, 6;
  const Mesh bowtie = make_mesh(x, t);
  const auto parts = split_components(bowtie);
  ASSERT_EQ(parts.size(), 2u);
  for (const Mesh& p : parts) {
    EXPECT_EQ(p.n_faces(), 2u);
    EXPECT_EQ(p.n_vertices(), 4u);
    expect_no_isolated_vertex(p);
  }
  const ComponentSelection one = keep_components(bowtie, {.keep_largest = 1});
  EXPECT_EQ(one.mesh.n_faces(), 2u);
  EXPECT_EQ(one.mesh.n_vertices(), 4u);
}

} // namespace
} // namespace sdflow
