//! Hostile files at the reader and validator level (issue 13, defects 2, 5 and 12): values out of
//! their declared type, byte order marks, bow-tie polygons, coordinates whose products overflow,
//! flat closed surfaces. Each is read right or refused with its code, never mis-read.
#include "io/temp_dir.h"

#include "sdflow/io/io.h"
#include "sdflow/io/validate.h"

#include <gtest/gtest.h>

#include <string>

namespace sdflow {
namespace {

//! The codes of the MeshValidationError that reading `file` throws (a failure if it does not).
std::vector<std::string> error_codes(const std::filesystem::path& file)
{
  try {
    read_mesh(file);
  } catch (const MeshValidationError& e) {
    std::vector<std::string> codes;
    for (const Finding& f : e.findings())
      codes.push_back(f.code);
    return codes;
  }
  ADD_FAILURE() << file << " was accepted";
  return {};
}

bool has(const std::vector<std::string>& codes, const std::string& code)
{
  return std::find(codes.begin(), codes.end(), code) != codes.end();
}

const std::string tetra_vertices = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";

TEST(HostileFiles, ascii_ply_value_out_of_range_of_its_declared_type_is_refused)
{
  test::TempDir dir;
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 4\nproperty uchar x\nproperty float y\n"
                             "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string faces = "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  test::write_file(dir / "bad.ply", header + "300 0 0\n1 0 0\n0 1 0\n0 0 1\n" + faces);
  try {
    read_polygon_soup(dir / "bad.ply");
    ADD_FAILURE() << "300 read as a uchar";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("out of range for property 'x' of type uchar"), std::string::npos) << e.what();
  }
  for (const std::string bad : {"-1 0 0\n", "2.5 0 0\n"}) {
    test::write_file(dir / "bad.ply", header + bad + "1 0 0\n0 1 0\n0 0 1\n" + faces);
    EXPECT_THROW(read_polygon_soup(dir / "bad.ply"), IoError) << bad;
  }
  test::write_file(dir / "list.ply", header + "0 0 0\n1 0 0\n0 1 0\n0 0 1\n" + "256 0 2 1\n" + faces.substr(8));
  EXPECT_THROW(read_polygon_soup(dir / "list.ply"), IoError) << "a list length of 256 in a uchar";
  test::write_file(dir / "good.ply", header + "255 0 0\n1 0 0\n0 1 0\n0 0 1\n" + faces);
  EXPECT_EQ(read_polygon_soup(dir / "good.ply").points[0].x(), 255.0);
}

TEST(HostileFiles, utf8_byte_order_mark_is_accepted_by_every_text_format)
{
  test::TempDir dir;
  const std::string bom = "\xEF\xBB\xBF";
  const std::pair<const char*, std::string> files[] = {
      {"t.off", "OFF\n4 4 0\n" + tetra_vertices + "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"},
      {"t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"},
      {"t.ply", "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                "element face 4\nproperty list uchar int vertex_indices\nend_header\n" +
                    tetra_vertices + "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"},
      {"t.stl", "solid t\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 1 0 0\nendloop\nendfacet\n"
                "facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 0 1\nendloop\nendfacet\n"
                "facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0 1\nvertex 0 1 0\nendloop\nendfacet\n"
                "facet normal 0 0 0\nouter loop\nvertex 1 0 0\nvertex 0 1 0\nvertex 0 0 1\nendloop\nendfacet\n"
                "endsolid t\n"}};
  for (const auto& [name, text] : files) {
    SCOPED_TRACE(name);
    test::write_file(dir / name, text);
    const BuiltMesh plain = read_mesh(dir / name);
    test::write_file(dir / name, bom + text);
    const BuiltMesh marked = read_mesh(dir / name);
    ASSERT_EQ(marked.mesh.n_vertices(), 4u) << "no vertex may be lost to the mark";
    EXPECT_EQ(marked.mesh.n_faces(), plain.mesh.n_faces());
    for (auto v : plain.mesh.vertices())
      EXPECT_EQ(marked.mesh.point(v), plain.mesh.point(v));
  }
}

TEST(HostileFiles, bow_tie_polygon_is_refused_not_triangulated)
{
  test::TempDir dir;
  // The square 0 1 2 3 visited as 0 2 1 3: its outline crosses itself.
  test::write_file(dir / "bowtie.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 2 1 3\n");
  EXPECT_TRUE(has(error_codes(dir / "bowtie.off"), "self-intersecting-face"));
  // Not symmetric (Newell's normal is not zero), and a pentagon whose edges cross.
  test::write_file(dir / "skew.off", "OFF\n4 1 0\n0 0 0\n2 0 0\n0 1 0\n2 1.5 0\n4 0 1 2 3\n");
  EXPECT_TRUE(has(error_codes(dir / "skew.off"), "self-intersecting-face"));
  test::write_file(dir / "star.off", "OFF\n5 1 0\n0 1 0\n0.588 -0.809 0\n-0.951 0.309 0\n0.951 0.309 0\n"
                                     "-0.588 -0.809 0\n5 0 1 2 3 4\n");
  EXPECT_TRUE(has(error_codes(dir / "star.off"), "self-intersecting-face"));
  // A simple non-convex polygon is still triangulated.
  test::write_file(dir / "l.off", "OFF\n6 1 0\n0 0 0\n2 0 0\n2 1 0\n1 1 0\n1 2 0\n0 2 0\n6 0 1 2 3 4 5\n");
  EXPECT_EQ(read_mesh(dir / "l.off").mesh.n_faces(), 4u);
}

TEST(HostileFiles, coordinates_whose_areas_overflow_are_refused_as_such)
{
  test::TempDir dir;
  test::write_file(dir / "huge.off", "OFF\n6 8 0\n1e200 0 0\n-1e200 0 0\n0 1e200 0\n0 -1e200 0\n0 0 1e200\n"
                                     "0 0 -1e200\n3 0 2 4\n3 2 1 4\n3 1 3 4\n3 3 0 4\n3 2 0 5\n3 1 2 5\n3 3 1 5\n"
                                     "3 0 3 5\n");
  const auto codes = error_codes(dir / "huge.off");
  EXPECT_TRUE(has(codes, "coordinate-too-large"));
  EXPECT_FALSE(has(codes, "zero-area-face")) << "the faces are not collinear";
  test::write_file(dir / "big.off", "OFF\n6 8 0\n1e50 0 0\n-1e50 0 0\n0 1e50 0\n0 -1e50 0\n0 0 1e50\n"
                                    "0 0 -1e50\n3 0 2 4\n3 2 1 4\n3 1 3 4\n3 3 0 4\n3 2 0 5\n3 1 2 5\n3 3 1 5\n"
                                    "3 0 3 5\n");
  EXPECT_NO_THROW(read_mesh(dir / "big.off"));
}

TEST(HostileFiles, flat_closed_surfaces_are_refused_with_zero_volume_component)
{
  test::TempDir dir;
  test::write_file(dir / "sheet.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 2 1\n");
  EXPECT_TRUE(has(error_codes(dir / "sheet.off"), "zero-volume-component"));
  test::write_file(dir / "flat.off", "OFF\n6 8 0\n1 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0.2 0.3 0\n-0.2 -0.3 0\n3 0 2 4\n"
                                     "3 2 1 4\n3 1 3 4\n3 3 0 4\n3 2 0 5\n3 1 2 5\n3 3 1 5\n3 0 3 5\n");
  EXPECT_TRUE(has(error_codes(dir / "flat.off"), "zero-volume-component"));
  // A thin but genuine body is kept.
  test::write_file(dir / "thin.off", "OFF\n6 8 0\n1 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0 0 1e-3\n0 0 -1e-3\n3 0 2 4\n"
                                     "3 2 1 4\n3 1 3 4\n3 3 0 4\n3 2 0 5\n3 1 2 5\n3 3 1 5\n3 0 3 5\n");
  EXPECT_NO_THROW(read_mesh(dir / "thin.off"));
}

// Found by fuzz/fuzz_read_ply: a binary element without properties and a huge count ran forever.
TEST(HostileFiles, ply_element_without_properties_is_refused_at_once)
{
  test::TempDir dir;
  test::write_file(dir / "empty.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 0\nproperty float x\n"
                                      "property float y\nproperty float z\nelement nothing 9000000000000000000\n"
                                      "end_header\n");
  try {
    read_polygon_soup(dir / "empty.ply");
    ADD_FAILURE() << "accepted";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("no properties"), std::string::npos) << e.what();
  }
  const std::string replay = std::string(SDFLOW_SOURCE_DIR) + "/fuzz/corpus/ply/regression_element_without_properties.ply";
  EXPECT_THROW(read_mesh(replay), IoError);
}

} // namespace
} // namespace sdflow
