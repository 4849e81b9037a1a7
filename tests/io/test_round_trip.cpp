//! Writing then reading a mesh gives back the same points, bit for bit, and the same triangles.

#include "io/temp_dir.h"
#include "support/analytic_meshes.h"

#include "sdflow/io/io.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <array>
#include <string>
#include <vector>

namespace sdflow {
namespace {

using Corners = std::array<Eigen::Vector3d, 3>;

//! A torus moved off the axes so that its coordinates are arbitrary doubles (no short decimals).
Mesh awkward_torus()
{
  Mesh mesh = analytic::torus(14, 9, 1.0, 0.37);
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  VertexVectors x = vertex_positions(mesh);
  for (Eigen::Index i = 0; i < x.rows(); ++i)
    x.row(i) = (rotation * x.row(i).transpose() / 3.0 + Eigen::Vector3d(1e3 / 7.0, -2.0 / 9.0, 1e-5)).transpose();
  set_vertex_positions(mesh, x);
  return mesh;
}

//! The same mesh with every coordinate rounded to float, which binary STL stores exactly.
Mesh rounded_to_float(Mesh mesh)
{
  VertexVectors x = vertex_positions(mesh);
  x = x.cast<float>().cast<double>();
  set_vertex_positions(mesh, x);
  return mesh;
}

//! Each face's corners, rotated to start at the smallest vertex index of the face (OpenMesh may
//! start a face at any of its corners).
std::vector<Corners> face_corners(const Mesh& mesh)
{
  std::vector<Corners> faces;
  for (auto f : mesh.faces()) {
    std::array<Mesh::VertexHandle, 3> v;
    int k = 0;
    for (auto h : f.vertices())
      v[k++] = h;
    int first = 0;
    for (int i = 1; i < 3; ++i)
      if (mesh.point(v[i]) < mesh.point(v[first]))
        first = i;
    faces.push_back({to_eigen(mesh.point(v[first])), to_eigen(mesh.point(v[(first + 1) % 3])),
                     to_eigen(mesh.point(v[(first + 2) % 3]))});
  }
  return faces;
}

struct Case {
  std::string extension;
  Encoding encoding;
};

class RoundTrip : public testing::TestWithParam<Case> {};

TEST_P(RoundTrip, keeps_points_bit_exact_and_faces)
{
  const Case c = GetParam();
  const bool float_only = c.extension == "stl" && c.encoding == Encoding::binary;
  const Mesh original = float_only ? rounded_to_float(awkward_torus()) : awkward_torus();
  test::TempDir dir;
  const auto file = dir / ("torus." + c.extension);
  write_mesh(original, file, {.encoding = c.encoding});
  const BuiltMesh read = read_mesh(file);

  ASSERT_EQ(read.mesh.n_vertices(), original.n_vertices());
  ASSERT_EQ(read.mesh.n_faces(), original.n_faces());
  if (c.extension != "stl") {
    // Indexed formats keep the vertex order and the face order.
    for (auto v : original.vertices()) {
      const auto p = original.point(v), q = read.mesh.point(v);
      ASSERT_TRUE(p[0] == q[0] && p[1] == q[1] && p[2] == q[2]) << "vertex " << v.idx();
    }
    EXPECT_TRUE(read.findings.empty());
  } else {
    ASSERT_EQ(read.findings.size(), 1u);
    EXPECT_EQ(read.findings.front().code, "duplicate-vertices-merged");
  }
  // Every format keeps the faces in order, with their corners in the same cyclic order.
  const auto before = face_corners(original), after = face_corners(read.mesh);
  for (std::size_t f = 0; f < before.size(); ++f)
    for (int k = 0; k < 3; ++k)
      ASSERT_EQ(before[f][k], after[f][k]) << "face " << f << " corner " << k;
}

INSTANTIATE_TEST_SUITE_P(EveryFormat, RoundTrip,
                         testing::Values(Case{"off", Encoding::ascii}, Case{"obj", Encoding::ascii},
                                         Case{"ply", Encoding::ascii}, Case{"ply", Encoding::binary},
                                         Case{"stl", Encoding::ascii}, Case{"stl", Encoding::binary},
                                         Case{"vtp", Encoding::binary}),
                         [](const testing::TestParamInfo<Case>& info) {
                           return info.param.extension + (info.param.encoding == Encoding::binary ? "_binary" : "_ascii");
                         });

TEST(RoundTrip, extreme_doubles_survive_text_formats)
{
  // Subnormal, huge and negative-zero coordinates stress the {:.17g} formatting and the parser.
  Mesh mesh = make_mesh((VertexVectors(4, 3) << 4.9406564584124654e-324, 0.1, 1.0 / 3.0,  //
                         1.7976931348623157e308 / 4, -0.0, 2.0 / 3.0,                       //
                         -1e-300, 1e300, 0.7,                                               //
                         3.0, 1e-7, -1e300)
                            .finished(),
                        (FaceIndices(1, 3) << 0, 1, 2).finished());
  test::TempDir dir;
  for (const std::string extension : {"off", "obj", "ply", "vtp"}) {
    SCOPED_TRACE(extension);
    const auto file = dir / ("extreme." + extension);
    write_mesh(mesh, file);
    const PolygonSoup soup = read_polygon_soup(file);
    ASSERT_EQ(soup.points.size(), 4u);
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) {
        const double written = mesh.point(Mesh::VertexHandle(i))[k];
        EXPECT_EQ(std::signbit(soup.points[i][k]), std::signbit(written));
        EXPECT_EQ(soup.points[i][k], written) << "vertex " << i << " coordinate " << k;
      }
  }
}

TEST(RoundTrip, format_follows_extension_case_insensitively)
{
  EXPECT_EQ(format_from_extension("a/b.OFF"), MeshFormat::off);
  EXPECT_EQ(format_from_extension("b.Obj"), MeshFormat::obj);
  EXPECT_EQ(format_from_extension("c.ply"), MeshFormat::ply);
  EXPECT_EQ(format_from_extension("d.StL"), MeshFormat::stl);
  EXPECT_EQ(format_from_extension("e.VTP"), MeshFormat::vtp);
  EXPECT_THROW(format_from_extension("e.vtk"), IoError);
  EXPECT_THROW(format_from_extension("noextension"), IoError);
}

} // namespace
} // namespace sdflow
