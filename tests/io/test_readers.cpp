//! The readers accept the variants real files use: comments, colours, negative OBJ indices,
//! polygons, any PLY scalar type and byte order, binary STL that begins with "solid".

#include "io/temp_dir.h"
#include "support/analytic_meshes.h"

#include "sdflow/io/io.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace sdflow {
namespace {

using Polygons = std::vector<std::vector<long long>>;

PolygonSoup read_text(const test::TempDir& dir, const std::string& name, const std::string& text)
{
  test::write_file(dir / name, text);
  return read_polygon_soup(dir / name);
}

TEST(ReadOff, skips_comments_blank_lines_and_colour_columns)
{
  test::TempDir dir;
  const PolygonSoup soup = read_text(dir, "colour.off",
                                     "# a tetrahedron with colours\n"
                                     "COFF\n"
                                     "\n"
                                     "4 4 6  # counts\n"
                                     "0 0 0 255 0 0 255\n"
                                     "1 0 0 0 255 0 255\n"
                                     "# comment between vertices\n"
                                     "0 1 0 0 0 255 255\n"
                                     "0 0 1 9 9 9 255\n"
                                     "3 0 2 1 0.5 0.5 0.5\n"
                                     "3 0 1 3\n"
                                     "\n"
                                     "3 1 2 3 1 0 0\n"
                                     "3 2 0 3\n");
  ASSERT_EQ(soup.points.size(), 4u);
  EXPECT_EQ(soup.points[3], Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(soup.polygons, (Polygons{{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}}));
  EXPECT_EQ(soup.point_lines, (std::vector<std::size_t>{5, 6, 8, 9}));
  EXPECT_EQ(soup.polygon_lines, (std::vector<std::size_t>{10, 11, 13, 14}));
}

TEST(ReadOff, accepts_counts_on_the_keyword_line_or_no_keyword)
{
  test::TempDir dir;
  const std::string body = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  EXPECT_EQ(read_text(dir, "a.off", "OFF 3 1 0\n" + body).polygons, (Polygons{{0, 1, 2}}));
  EXPECT_EQ(read_text(dir, "b.off", "3 1 3\n" + body).polygons, (Polygons{{0, 1, 2}}));
  EXPECT_EQ(read_text(dir, "c.off", "OFF\r\n3 1\r\n0 0 0\r\n+1 0 0\r\n0 1e0 0\r\n4 0 1 2 0\r\n").points[1],
            Eigen::Vector3d(1, 0, 0));
}

TEST(ReadObj, resolves_negative_indices_and_slashed_corners)
{
  test::TempDir dir;
  const PolygonSoup soup = read_text(dir, "square.obj",
                                     "# square then a triangle\n"
                                     "mtllib none.mtl\n"
                                     "o square\n"
                                     "v 0 0 0\n"
                                     "v 1 0 0 1.0\n"
                                     "v 1 1 0 0.5 0.5 0.5\n"
                                     "v 0 1 0\n"
                                     "vt 0 0\n"
                                     "vn 0 0 1\n"
                                     "usemtl red\n"
                                     "s off\n"
                                     "f 1/1/1 2/1/1 3//1 4/1\n"
                                     "v 0 0 1\n"
                                     "g tail\n"
                                     "f -1 -4/1 -5//1\n"
                                     "l 1 2\n");
  ASSERT_EQ(soup.points.size(), 5u);
  EXPECT_EQ(soup.points[1], Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(soup.polygons, (Polygons{{0, 1, 2, 3}, {4, 1, 0}}));
  EXPECT_EQ(soup.polygon_lines, (std::vector<std::size_t>{12, 15}));
}

//! A PLY header with extra vertex properties, a face list of unusual types, and an extra element.
std::string unusual_ply_header(const std::string& format)
{
  return "ply\n"
         "format " + format + " 1.0\n"
         "comment made by hand\n"
         "obj_info nothing\n"
         "element vertex 4\n"
         "property uchar flags\n"
         "property float x\n"
         "property double y\n"
         "property short z\n"
         "property list uchar float extra\n"
         "element face 2\n"
         "property int material\n"
         "property list uint ushort vertex_index\n"
         "element edge 1\n"
         "property int vertex1\n"
         "property int vertex2\n"
         "end_header\n";
}

const std::vector<Eigen::Vector3d> unusual_points = {{0, 0, 0}, {1.5, 0, 0}, {0, 2.25, 0}, {0, 0, -3}};
const Polygons unusual_faces = {{0, 2, 1}, {0, 1, 2, 3}};

TEST(ReadPly, ascii_skips_other_properties_and_elements)
{
  test::TempDir dir;
  const PolygonSoup soup = read_text(dir, "unusual.ply",
                                     unusual_ply_header("ascii") +
                                         "7 0 0 0 0\n"
                                         "7 1.5 0 0 2 9 9\n"
                                         "7 0 2.25 0 1 4\n"
                                         "7 0 0 -3 0\n"
                                         "5 3 0 2 1\n"
                                         "5 4 0 1 2 3\n"
                                         "0 1\n");
  EXPECT_EQ(soup.points, unusual_points);
  EXPECT_EQ(soup.polygons, unusual_faces);
  EXPECT_EQ(soup.point_lines, (std::vector<std::size_t>{18, 19, 20, 21}));
}

//! Append `value` in the given byte order.
template <class T>
void put(std::string& out, T value, std::endian order)
{
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if (order != std::endian::native)
    std::reverse(bytes, bytes + sizeof(T));
  out.append(bytes, sizeof(T));
}

std::string unusual_binary_ply(std::endian order)
{
  std::string ply = unusual_ply_header(order == std::endian::big ? "binary_big_endian" : "binary_little_endian");
  for (const auto& p : unusual_points) {
    put<std::uint8_t>(ply, 7, order);
    put<float>(ply, static_cast<float>(p.x()), order);
    put<double>(ply, p.y(), order);
    put<std::int16_t>(ply, static_cast<std::int16_t>(p.z()), order);
    put<std::uint8_t>(ply, 1, order);
    put<float>(ply, 42.0f, order);
  }
  for (const auto& face : unusual_faces) {
    put<std::int32_t>(ply, 5, order);
    put<std::uint32_t>(ply, static_cast<std::uint32_t>(face.size()), order);
    for (const long long i : face)
      put<std::uint16_t>(ply, static_cast<std::uint16_t>(i), order);
  }
  put<std::int32_t>(ply, 0, order);
  put<std::int32_t>(ply, 1, order);
  return ply;
}

TEST(ReadPly, binary_in_both_byte_orders)
{
  test::TempDir dir;
  for (const auto order : {std::endian::big, std::endian::little}) {
    SCOPED_TRACE(order == std::endian::big ? "big endian" : "little endian");
    const PolygonSoup soup = read_text(dir, "unusual.ply", unusual_binary_ply(order));
    EXPECT_EQ(soup.points, unusual_points);
    EXPECT_EQ(soup.polygons, unusual_faces);
  }
}

TEST(ReadStl, binary_file_starting_with_solid_is_read_as_binary)
{
  test::TempDir dir;
  const Mesh cube_like = analytic::icosphere(1);
  write_mesh(cube_like, dir / "sphere.stl", {.encoding = Encoding::binary});
  std::string bytes = test::read_file(dir / "sphere.stl");
  const std::string header = "solid sphere exported by a careless tool";
  std::memcpy(bytes.data(), header.data(), header.size());
  test::write_file(dir / "solid.stl", bytes);
  const BuiltMesh read = read_mesh(dir / "solid.stl");
  EXPECT_EQ(read.mesh.n_faces(), cube_like.n_faces());
  EXPECT_EQ(read.mesh.n_vertices(), cube_like.n_vertices());
}

TEST(ReadStl, ascii_with_several_solids_and_any_keyword_case)
{
  test::TempDir dir;
  const PolygonSoup soup = read_text(dir, "two.stl",
                                     "solid first\n"
                                     "  facet normal 0 0 1\n"
                                     "    outer loop\n"
                                     "      vertex 0 0 0\n"
                                     "      vertex 1 0 0\n"
                                     "      vertex 0 1 0\n"
                                     "    endloop\n"
                                     "  endfacet\n"
                                     "endsolid first\n"
                                     "SOLID second\n"
                                     "FACET NORMAL 0 0 1\n"
                                     "OUTER LOOP\n"
                                     "VERTEX 1 0 0\n"
                                     "VERTEX 1 1 0\n"
                                     "VERTEX 0 1 0\n"
                                     "ENDLOOP\n"
                                     "ENDFACET\n"
                                     "ENDSOLID\n");
  ASSERT_EQ(soup.points.size(), 6u);
  EXPECT_EQ(soup.polygons, (Polygons{{0, 1, 2}, {3, 4, 5}}));
  EXPECT_EQ(soup.polygon_lines, (std::vector<std::size_t>{2, 11}));
  EXPECT_EQ(soup.point_lines[4], 14u);
}

} // namespace
} // namespace sdflow
