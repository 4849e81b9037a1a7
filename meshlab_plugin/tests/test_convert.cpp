//! Tests of convert.h: CMeshO ↔ Surface and MeshLab's float parameters.

#include "convert.h"

#include "sdflow/errors.h"

#include <vcg/complex/algorithms/create/platonic.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <stdexcept>

namespace {

using sdflow::meshlab::ShadedSurface;
using sdflow::meshlab::Surface;

//! Makes `mesh` an octahedron with vertices off the float grid's round numbers (so a lossy conversion shows).
void make_octahedron(CMeshO& mesh)
{
  vcg::tri::Octahedron(mesh);
  for (auto& v : mesh.vert)
    v.P() = v.P() * Scalarm(1.2345678f) + Point3m(0.1f, -0.3f, 7.7f);
}

std::size_t stored_index(const CMeshO& mesh, const CVertexO* v) { return vcg::tri::Index(mesh, v); }

//! The surface with made-up normals and curvatures (one distinct value per vertex).
ShadedSurface shade(const Surface& surface)
{
  ShadedSurface shaded{surface, {}, {}};
  for (std::size_t i = 0; i < surface.points.size(); ++i) {
    shaded.normals.push_back({0.0, 0.0, 1.0});
    shaded.mean_curvature.push_back(-0.25 * double(i + 1));
  }
  return shaded;
}

TEST(Convert, surface_holds_the_exact_float_coordinates_and_the_triangles)
{
  CMeshO mesh;
  make_octahedron(mesh);
  const Surface surface = sdflow::meshlab::to_surface(mesh);
  ASSERT_EQ(surface.points.size(), mesh.vert.size());
  ASSERT_EQ(surface.triangles.size(), mesh.face.size());
  for (std::size_t i = 0; i < mesh.vert.size(); ++i)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(surface.points[i][k], double(mesh.vert[i].cP()[k])) << "vertex " << i << " coordinate " << k;
  for (std::size_t f = 0; f < mesh.face.size(); ++f)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(std::size_t(surface.triangles[f][k]), stored_index(mesh, mesh.face[f].cV(k))) << "face " << f;
}

TEST(Convert, round_trip_through_replace_mesh_is_lossless)
{
  CMeshO original;
  make_octahedron(original);
  const Surface surface = sdflow::meshlab::to_surface(original);
  CMeshO copy;
  vcg::tri::Tetrahedron(copy); // something else to be replaced
  sdflow::meshlab::replace_mesh(copy, shade(surface));
  ASSERT_EQ(copy.vn, original.vn);
  ASSERT_EQ(copy.fn, original.fn);
  for (std::size_t i = 0; i < original.vert.size(); ++i)
    EXPECT_EQ(copy.vert[i].cP(), original.vert[i].cP()) << "vertex " << i;
  for (std::size_t f = 0; f < original.face.size(); ++f)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(stored_index(copy, copy.face[f].cV(k)), stored_index(original, original.face[f].cV(k)))
          << "face " << f;
}

TEST(Convert, replace_mesh_stores_curvature_as_quality_and_the_given_normals)
{
  CMeshO mesh;
  make_octahedron(mesh);
  ShadedSurface shaded = shade(sdflow::meshlab::to_surface(mesh));
  shaded.normals[2] = {0.6, 0.0, -0.8};
  sdflow::meshlab::replace_mesh(mesh, shaded);
  for (std::size_t i = 0; i < mesh.vert.size(); ++i)
    EXPECT_EQ(mesh.vert[i].cQ(), float(shaded.mean_curvature[i])) << "vertex " << i;
  EXPECT_EQ(mesh.vert[2].cN(), Point3m(0.6f, 0.0f, -0.8f));
}

TEST(Convert, replace_mesh_recomputes_face_normals_and_bounding_box)
{
  constexpr float normal_tolerance = 1e-6f;
  CMeshO mesh;
  Surface surface;
  surface.points = {{0, 0, 0}, {2, 0, 0}, {0, 3, 0}};
  surface.triangles = {{0, 1, 2}};
  sdflow::meshlab::replace_mesh(mesh, shade(surface));
  EXPECT_NEAR(mesh.face[0].cN()[2], 1.0f, normal_tolerance); // counter-clockwise seen from +z
  EXPECT_EQ(mesh.bbox.min, Point3m(0, 0, 0));
  EXPECT_EQ(mesh.bbox.max, Point3m(2, 3, 0));
}

TEST(Convert, deleted_elements_are_skipped_and_the_rest_renumbered)
{
  CMeshO mesh;
  make_octahedron(mesh);
  // Delete vertex 0 and the faces around it, as MeshLab's editing filters do (marks, no erase).
  CVertexO* gone = &mesh.vert[0];
  for (auto& face : mesh.face)
    if (face.V(0) == gone || face.V(1) == gone || face.V(2) == gone)
      vcg::tri::Allocator<CMeshO>::DeleteFace(mesh, face);
  vcg::tri::Allocator<CMeshO>::DeleteVertex(mesh, *gone);

  const Surface surface = sdflow::meshlab::to_surface(mesh);
  ASSERT_EQ(surface.points.size(), std::size_t(mesh.vn));
  ASSERT_EQ(surface.triangles.size(), std::size_t(mesh.fn));
  for (std::size_t i = 1; i < mesh.vert.size(); ++i)
    EXPECT_EQ(surface.points[i - 1][0], double(mesh.vert[i].cP()[0])) << "vertex " << i;
  std::size_t t = 0;
  for (const auto& face : mesh.face) {
    if (face.IsD())
      continue;
    SCOPED_TRACE("triangle " + std::to_string(t));
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(std::size_t(surface.triangles[t][k]), stored_index(mesh, face.cV(k)) - 1);
    ++t;
  }
}

TEST(Convert, live_face_on_a_deleted_vertex_is_an_invalid_mesh)
{
  CMeshO mesh;
  make_octahedron(mesh);
  vcg::tri::Allocator<CMeshO>::DeleteVertex(mesh, mesh.vert[0]);
  EXPECT_THROW(sdflow::meshlab::to_surface(mesh), sdflow::InvalidMesh);
}

TEST(Convert, inconsistent_surface_is_refused_and_the_mesh_left_alone)
{
  CMeshO mesh;
  make_octahedron(mesh);
  const Point3m first = mesh.vert[0].cP();
  ShadedSurface missing_normal = shade(sdflow::meshlab::to_surface(mesh));
  missing_normal.normals.pop_back();
  EXPECT_THROW(sdflow::meshlab::replace_mesh(mesh, missing_normal), std::invalid_argument);
  ShadedSurface bad_index = shade(sdflow::meshlab::to_surface(mesh));
  bad_index.surface.triangles[3][1] = int(bad_index.surface.points.size());
  EXPECT_THROW(sdflow::meshlab::replace_mesh(mesh, bad_index), std::invalid_argument);
  EXPECT_EQ(mesh.vn, 6);
  EXPECT_EQ(mesh.fn, 8);
  EXPECT_EQ(mesh.vert[0].cP(), first);
}

TEST(Convert, intended_double_is_the_decimal_the_user_typed)
{
  EXPECT_EQ(sdflow::meshlab::intended_double(0.001f), 0.001);
  EXPECT_EQ(sdflow::meshlab::intended_double(0.5f), 0.5);
  EXPECT_EQ(sdflow::meshlab::intended_double(1e-7f), 1e-7);
  EXPECT_EQ(sdflow::meshlab::intended_double(2.5e-5f), 2.5e-5);
  EXPECT_EQ(sdflow::meshlab::intended_double(-3.3f), -3.3);
  EXPECT_EQ(sdflow::meshlab::intended_double(0.0f), 0.0);
  EXPECT_TRUE(std::isinf(sdflow::meshlab::intended_double(std::numeric_limits<float>::infinity())));
}

TEST(Convert, intended_double_rounds_back_to_the_same_float)
{
  constexpr int samples = 10000;
  std::mt19937 random(7);
  std::uniform_int_distribution<std::uint32_t> bits(0, 0x7f7fffffu); // positive finite floats
  for (int i = 0; i < samples; ++i) {
    const std::uint32_t pattern = bits(random);
    float value;
    std::memcpy(&value, &pattern, sizeof value);
    SCOPED_TRACE(value);
    EXPECT_EQ(float(sdflow::meshlab::intended_double(value)), value);
  }
}

} // namespace
