//! The .vtp reader: the encodings VTK writes (ascii, inline base64, appended raw and base64, UInt32
//! and UInt64 headers, either byte order) give the same surface, and what is not a surface of
//! polygons, or is damaged, is refused with a reason that names the file.

#include "io/temp_dir.h"

#include "sdflow/errors.h"
#include "sdflow/io/detail/base64.h"
#include "sdflow/io/detail/formats.h"
#include "sdflow/io/io.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace sdflow {
namespace {

// A unit square in the plane z = 0 as two triangles, and a field on its four corners.
const std::vector<double> square_points = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
const std::vector<std::int32_t> square_connectivity = {0, 1, 2, 0, 2, 3};
const std::vector<std::int32_t> square_offsets = {3, 6};
const std::vector<double> square_h = {0.5, -0.25, 1e-300, 3};

template <class T>
std::string bytes_of(const std::vector<T>& values, bool big_endian)
{
  std::string bytes;
  for (T v : values) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    if (big_endian)
      std::reverse(b, b + sizeof(T));
    bytes.append(b, sizeof(T));
  }
  return bytes;
}

template <class Header>
std::string with_header(const std::string& data, bool big_endian)
{
  return bytes_of<Header>({static_cast<Header>(data.size())}, big_endian) + data;
}

std::string document(const std::string& vtkfile_attributes, const std::string& arrays, const std::string& tail = "")
{
  return fmt::format("<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" {}>\n<PolyData>\n"
                     "<Piece NumberOfPoints=\"4\" NumberOfPolys=\"2\">\n{}</Piece>\n</PolyData>\n{}</VTKFile>\n",
                     vtkfile_attributes, arrays, tail);
}

//! The square with each array written by `array(type, name, components, index)`.
template <class Array>
std::string square(const std::string& attributes, Array array, const std::string& tail = "")
{
  return document(attributes,
                  "<PointData Scalars=\"H\">\n" + array("Float64", "H", 1, 0) + "</PointData>\n<Points>\n" +
                      array("Float64", "Points", 3, 1) + "</Points>\n<Polys>\n" +
                      array("Int32", "connectivity", 1, 2) + array("Int32", "offsets", 1, 3) + "</Polys>\n",
                  tail);
}

std::vector<std::string> square_blocks(bool big_endian)
{
  return {bytes_of(square_h, big_endian), bytes_of(square_points, big_endian),
          bytes_of(square_connectivity, big_endian), bytes_of(square_offsets, big_endian)};
}

void expect_square(const PolygonSoup& soup)
{
  ASSERT_EQ(soup.points.size(), 4u);
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(soup.points[i][k], square_points[3 * i + k]);
  ASSERT_EQ(soup.polygons.size(), 2u);
  EXPECT_EQ(soup.polygons[0], (std::vector<long long>{0, 1, 2}));
  EXPECT_EQ(soup.polygons[1], (std::vector<long long>{0, 2, 3}));
  ASSERT_EQ(soup.vertex_fields.size(), 1u);
  EXPECT_EQ(soup.vertex_fields[0].name, "H");
  for (int i = 0; i < 4; ++i)
    EXPECT_EQ(soup.vertex_fields[0].values(i, 0), square_h[i]);
}

PolygonSoup read(const std::string& text) { return detail::read_vtp(text, "square.vtp"); }

TEST(Vtp, ascii_arrays)
{
  const std::string text = square("version=\"0.1\" byte_order=\"LittleEndian\"",
                                   [](const char* type, const char* name, int components, int index) {
    std::string values;
    if (index == 0)
      values = "0.5 -0.25 1e-300 3";
    else if (index == 1)
      values = "0 0 0  1 0 0\n1 1 0  0 1 0";
    else if (index == 2)
      values = "0 1 2 0 2 3";
    else
      values = "3 6";
    return fmt::format("<DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"ascii\">\n{}\n</DataArray>\n",
                       type, name, components, values);
  });
  expect_square(read(text));
}

TEST(Vtp, inline_base64_with_uint32_and_uint64_headers_in_both_byte_orders)
{
  for (const bool big_endian : {false, true})
    for (const bool wide : {false, true}) {
      SCOPED_TRACE(fmt::format("big endian {}, UInt64 {}", big_endian, wide));
      const std::vector<std::string> blocks = square_blocks(big_endian);
      const std::string attributes = fmt::format("version=\"1.0\" byte_order=\"{}\" header_type=\"{}\"",
                                                 big_endian ? "BigEndian" : "LittleEndian", wide ? "UInt64" : "UInt32");
      expect_square(read(square(attributes, [&](const char* type, const char* name, int components, int index) {
        const std::string block = wide ? with_header<std::uint64_t>(blocks[index], big_endian)
                                       : with_header<std::uint32_t>(blocks[index], big_endian);
        return fmt::format("<DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"binary\">\n  {}\n"
                           "</DataArray>\n", type, name, components, detail::encode_base64(block));
      })));
    }
}

TEST(Vtp, appended_raw_and_base64_also_with_headers_encoded_apart)
{
  const std::vector<std::string> blocks = square_blocks(false);
  for (const char* encoding : {"raw", "base64", "base64 apart"}) {
    SCOPED_TRACE(encoding);
    const std::string mode = encoding;
    std::string appended;
    std::vector<std::size_t> offsets;
    for (const std::string& block : blocks) {
      offsets.push_back(appended.size());
      const std::string header = bytes_of<std::uint64_t>({block.size()}, false);
      if (mode == "raw")
        appended += header + block;
      else if (mode == "base64")
        appended += detail::encode_base64(header + block);
      else
        appended += detail::encode_base64(header) + detail::encode_base64(block);
    }
    const std::string text = square(
        "version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\"",
        [&](const char* type, const char* name, int components, int index) {
          return fmt::format("<DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"appended\" "
                             "offset=\"{}\"/>\n", type, name, components, offsets[index]);
        },
        fmt::format("<AppendedData encoding=\"{}\">\n   _{}\n</AppendedData>\n", mode == "raw" ? "raw" : "base64",
                    appended));
    expect_square(read(text));
  }
}

TEST(Vtp, polygons_are_triangulated_as_by_the_other_readers)
{
  std::string text = document("byte_order=\"LittleEndian\"",
                              "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\">0 0 0 1 0 0 1 1 0 0 1 0"
                              "</DataArray></Points>\n<Polys><DataArray type=\"Int64\" Name=\"connectivity\">0 1 2 3"
                              "</DataArray><DataArray type=\"Int64\" Name=\"offsets\">4</DataArray></Polys>\n");
  text.replace(text.find("NumberOfPolys=\"2\""), 17, "NumberOfPolys=\"1\"");
  test::TempDir dir;
  test::write_file(dir / "quad.vtp", text);
  const BuiltMesh built = read_mesh(dir / "quad.vtp");
  EXPECT_EQ(built.mesh.n_faces(), 2u);
  bool triangulated = false;
  for (const auto& finding : built.findings)
    triangulated = triangulated || finding.code == "polygon-triangulated";
  EXPECT_TRUE(triangulated);
}

//! Reading `text` fails with IoError whose message names the file and holds `reason`.
void expect_refused(const std::string& text, const std::string& reason)
{
  try {
    read(text);
    ADD_FAILURE() << "accepted; expected: " << reason;
  } catch (const IoError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("square.vtp", 0), 0u) << message;
    EXPECT_NE(message.find(reason), std::string::npos) << message;
  }
}

TEST(Vtp, bad_files_are_refused_with_the_reason)
{
  const std::string ascii_points = "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\">0 0 0 1 0 0 1 1 0 0 1 0"
                                   "</DataArray></Points>\n";
  const std::string polys = "<Polys><DataArray type=\"Int32\" Name=\"connectivity\">0 1 2 0 2 3</DataArray>"
                            "<DataArray type=\"Int32\" Name=\"offsets\">3 6</DataArray></Polys>\n";
  expect_square(read(document("", "<PointData><DataArray type=\"Float64\" Name=\"H\">0.5 -0.25 1e-300 3</DataArray>"
                                  "</PointData>" + ascii_points + polys)));
  expect_refused("<VTKFile type=\"PolyData\"><PolyData><Piece", "not well-formed XML");
  expect_refused("just text", "not well-formed XML");
  expect_refused("<?xml version=\"1.0\"?><VTKFile type=\"UnstructuredGrid\"></VTKFile>",
                 "of type UnstructuredGrid; sdflow reads PolyData");
  expect_refused("<?xml version=\"1.0\"?><other/>", "not a VTK XML file");
  expect_refused(document("compressor=\"vtkZLibDataCompressor\"", ascii_points + polys), "compressed");
  {
    std::string lines = document("", ascii_points + polys);
    lines.replace(lines.find("NumberOfPolys"), 0, "NumberOfLines=\"1\" ");
    expect_refused(lines, "1 line");
  }
  expect_refused(document("", polys), "no <Points>");
  expect_refused(document("", "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\">0 0 0 1 0 0</DataArray>"
                              "</Points>" + polys),
                 "holds 6 values for NumberOfPoints=\"4\"");
  expect_refused(document("", "<Points><DataArray type=\"Float64\" NumberOfComponents=\"2\">0 0 1 0 1 1 0 1</DataArray>"
                              "</Points>" + polys),
                 "2 components, not 3");
  expect_refused(document("", ascii_points + "<Polys><DataArray type=\"Int32\" Name=\"connectivity\">0 1 2 3"
                                             "</DataArray><DataArray type=\"Int32\" Name=\"offsets\">2 4</DataArray>"
                                             "</Polys>"),
                 "polygon 0 spans connectivity [0, 2)");
  // An offset far below the last one (found by fuzz_read_vtp: the span's length overflowed).
  expect_refused(document("", ascii_points + "<Polys><DataArray type=\"Int64\" Name=\"connectivity\">0 1 2 0 2 3"
                                             "</DataArray><DataArray type=\"Int64\" Name=\"offsets\">3 "
                                             "-9223372036854775808</DataArray></Polys>"),
                 "polygon 1 spans connectivity [3, -9223372036854775808)");
  expect_refused(document("", ascii_points + "<Polys><DataArray type=\"Float32\" Name=\"connectivity\">0 1 2 0 2 3"
                                             "</DataArray><DataArray type=\"Int32\" Name=\"offsets\">3 6</DataArray>"
                                             "</Polys>"),
                 "cells need an integer type");
  expect_refused(document("", ascii_points + "<Polys><DataArray type=\"Int32\" Name=\"connectivity\">0 1 x 0 2 3"
                                             "</DataArray><DataArray type=\"Int32\" Name=\"offsets\">3 6</DataArray>"
                                             "</Polys>"),
                 "'x' is not an integer");
  expect_refused(document("", ascii_points + "<Polys><DataArray type=\"Int32\" Name=\"connectivity\">0 1 2 0 2 3 1"
                                             "</DataArray><DataArray type=\"Int32\" Name=\"offsets\">3 6</DataArray>"
                                             "</Polys>"),
                 "holds 7 entries but the offsets use 6");
  // Binary arrays whose data is missing or whose header lies.
  const std::string appended_points = "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"appended\" "
                                      "offset=\"0\"/></Points>" + polys;
  expect_refused(document("header_type=\"UInt64\"", appended_points, "<AppendedData encoding=\"raw\">_" +
                                                                         with_header<std::uint64_t>(std::string(40, 'a'), false)
                                                                             .substr(0, 20)),
                 "announces 40 bytes, more than the 23 left");
  expect_refused(document("header_type=\"UInt64\"", appended_points, "<AppendedData encoding=\"raw\">\n  no underscore"),
                 "must begin with '_'");
  expect_refused(document("", appended_points), "has no <AppendedData>");
  expect_refused(document("", "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"binary\">AAA*"
                              "</DataArray></Points>" + polys),
                 "base64 data is malformed or truncated");
  {
    std::string two = document("", ascii_points + polys);
    two.replace(two.find("</PolyData>"), 0, "<Piece NumberOfPoints=\"0\"/>");
    expect_refused(two, "several pieces");
  }
  {
    std::string huge = document("", ascii_points + polys);
    huge.replace(huge.find("NumberOfPoints=\"4\""), 18, "NumberOfPoints=\"9000000000000000000\"");
    expect_refused(huge, "are more than a file of");
  }
}

} // namespace
} // namespace sdflow
