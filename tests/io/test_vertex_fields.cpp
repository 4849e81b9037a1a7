//! Per-vertex data written with a surface (H, N, w) reads back from PLY and .vtp files bit for bit,
//! under the names other tools read (PLY: quality, nx ny nz).

#include "io/temp_dir.h"
#include "support/analytic_meshes.h"

#include "sdflow/errors.h"
#include "sdflow/io/io.h"
#include "sdflow/io/vtk.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace sdflow {
namespace {

constexpr double curvature_tolerance = 0.02; // relative, cotangent H on a level-3 icosphere
constexpr double normal_tolerance = 1e-3;    // radial unit normals on the same sphere

//! The field of `soup` named `name`; fails the test when absent.
const VertexField& field(const PolygonSoup& soup, const std::string& name)
{
  for (const VertexField& f : soup.vertex_fields)
    if (f.name == name)
      return f;
  ADD_FAILURE() << "no per-vertex field " << name;
  static const VertexField none;
  return none;
}

//! H, N and a w of awkward doubles (subnormal, huge, negative zero among them) on a sphere.
std::vector<VertexField> sphere_fields(const Mesh& mesh)
{
  std::vector<VertexField> fields = surface_fields(mesh);
  Eigen::VectorXd w(mesh.n_vertices());
  for (Eigen::Index i = 0; i < w.size(); ++i)
    w[i] = std::sin(1e3 * static_cast<double>(i)) / 7.0;
  w[0] = 4.9406564584124654e-324;
  w[1] = -0.0;
  w[2] = 1.7976931348623157e308;
  fields.push_back({"w", w});
  return fields;
}

void expect_bits(const Eigen::MatrixXd& read, const Eigen::MatrixXd& written, const std::string& what)
{
  ASSERT_EQ(read.rows(), written.rows()) << what;
  ASSERT_EQ(read.cols(), written.cols()) << what;
  for (Eigen::Index i = 0; i < read.rows(); ++i)
    for (Eigen::Index c = 0; c < read.cols(); ++c)
      ASSERT_TRUE(read(i, c) == written(i, c) && std::signbit(read(i, c)) == std::signbit(written(i, c)))
          << what << " row " << i << " column " << c << ": " << read(i, c) << " != " << written(i, c);
}

TEST(VertexFields, surface_fields_are_the_cotangent_curvature_and_outward_normals)
{
  const Mesh sphere = analytic::icosphere(3, 2.0);
  const std::vector<VertexField> fields = surface_fields(sphere);
  ASSERT_EQ(fields.size(), 2u);
  EXPECT_EQ(fields[0].name, "H");
  EXPECT_EQ(fields[1].name, "N");
  for (auto v : sphere.vertices()) {
    const Eigen::Vector3d p = to_eigen(sphere.point(v));
    EXPECT_NEAR(fields[0].values(v.idx(), 0), -1 / p.norm(), curvature_tolerance / p.norm());
    EXPECT_NEAR(fields[1].values.row(v.idx()).dot(p.normalized()), 1.0, normal_tolerance);
  }
}

TEST(VertexFields, surface_fields_are_left_out_where_normals_are_undefined)
{
  // A triangle and an isolated vertex: the vertex has no normal, so no field is written.
  const Mesh mesh = make_mesh((VertexVectors(4, 3) << 0, 0, 0, 1, 0, 0, 0, 1, 0, 5, 5, 5).finished(),
                              (FaceIndices(1, 3) << 0, 1, 2).finished());
  EXPECT_TRUE(surface_fields(mesh).empty());
}

TEST(VertexFields, ply_keeps_h_as_quality_n_as_normals_and_w_bit_for_bit)
{
  const Mesh sphere = analytic::icosphere(2, 1.7);
  const std::vector<VertexField> fields = sphere_fields(sphere);
  test::TempDir dir;
  for (const Encoding encoding : {Encoding::ascii, Encoding::binary}) {
    SCOPED_TRACE(encoding == Encoding::binary ? "binary" : "ascii");
    write_mesh(sphere, dir / "s.ply", {.encoding = encoding, .vertex_fields = fields});
    const std::string header = test::read_file(dir / "s.ply").substr(0, 400);
    for (const char* property : {"property double quality\n", "property double nx\n", "property double ny\n",
                                 "property double nz\n", "property double w\n"})
      EXPECT_NE(header.find(property), std::string::npos) << property;
    const PolygonSoup soup = read_polygon_soup(dir / "s.ply");
    ASSERT_EQ(soup.normals.size(), sphere.n_vertices());
    Eigen::MatrixXd normals(soup.normals.size(), 3);
    for (std::size_t i = 0; i < soup.normals.size(); ++i)
      normals.row(static_cast<Eigen::Index>(i)) = soup.normals[i].transpose();
    expect_bits(normals, fields[1].values, "nx ny nz");
    expect_bits(field(soup, "quality").values, fields[0].values, "quality");
    expect_bits(field(soup, "w").values, fields[2].values, "w");
    EXPECT_EQ(soup.vertex_fields.size(), 2u);
    // The mesh reads as before: the properties do not disturb the geometry.
    EXPECT_EQ(read_mesh(dir / "s.ply").mesh.n_faces(), sphere.n_faces());
  }
}

TEST(VertexFields, vtp_keeps_every_field_and_point_bit_for_bit)
{
  const Mesh sphere = analytic::icosphere(2, 1.7);
  const std::vector<VertexField> fields = sphere_fields(sphere);
  test::TempDir dir;
  write_vtp(sphere, fields, dir / "s.vtp");
  const PolygonSoup soup = read_polygon_soup(dir / "s.vtp");
  ASSERT_EQ(soup.points.size(), sphere.n_vertices());
  for (auto v : sphere.vertices())
    for (int k = 0; k < 3; ++k)
      ASSERT_EQ(soup.points[v.idx()][k], sphere.point(v)[k]);
  ASSERT_EQ(soup.vertex_fields.size(), 3u);
  for (std::size_t f = 0; f < fields.size(); ++f) {
    EXPECT_EQ(soup.vertex_fields[f].name, fields[f].name);
    expect_bits(soup.vertex_fields[f].values, fields[f].values, fields[f].name);
  }
  const FaceIndices triangles = face_indices(sphere);
  ASSERT_EQ(soup.polygons.size(), static_cast<std::size_t>(triangles.rows()));
  for (Eigen::Index f = 0; f < triangles.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      ASSERT_EQ(soup.polygons[f][k], triangles(f, k));
}

TEST(VertexFields, fields_that_do_not_fit_the_mesh_are_refused_with_their_name)
{
  const Mesh sphere = analytic::icosphere(1);
  test::TempDir dir;
  const auto refused = [&](const VertexField& f, const std::string& text) {
    for (const char* name : {"f.ply", "f.vtp"}) {
      try {
        write_mesh(sphere, dir / name, {.vertex_fields = {f}});
        ADD_FAILURE() << name << ": accepted " << f.name;
      } catch (const InvalidParameter& e) {
        EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
      }
      EXPECT_FALSE(std::filesystem::exists(dir / name));
    }
  };
  refused({"H", Eigen::VectorXd::Zero(3)}, "`H` is 3×1");
  refused({"N", Eigen::MatrixXd::Zero(sphere.n_vertices(), 2)}, "1 or 3 columns");
  refused({"two words", Eigen::VectorXd::Zero(sphere.n_vertices())}, "must be letters");
  try {
    write_mesh(sphere, dir / "x.ply", {.vertex_fields = {{"x", Eigen::VectorXd::Zero(sphere.n_vertices())}}});
    ADD_FAILURE() << "a field named x was written over the coordinate";
  } catch (const InvalidParameter& e) {
    EXPECT_NE(std::string(e.what()).find("PLY property `x` twice"), std::string::npos) << e.what();
  }
}

} // namespace
} // namespace sdflow
