//! Bad files give an IoError naming the file, the line (or element) and what was expected; never
//! a crash, whatever the cut of a truncated file.

#include "io/temp_dir.h"
#include "support/analytic_meshes.h"

#include "sdflow/io/io.h"

#include <gtest/gtest.h>

#include <initializer_list>
#include <string>
#include <vector>

namespace sdflow {
namespace {

//! The IoError message of reading `file`, or a failure if the read does not throw IoError.
std::string io_error_of(const std::filesystem::path& file)
{
  try {
    read_polygon_soup(file);
  } catch (const IoError& e) {
    return e.what();
  }
  ADD_FAILURE() << "reading " << file << " did not throw IoError";
  return {};
}

std::string io_error_of_text(const test::TempDir& dir, const std::string& name, const std::string& text)
{
  test::write_file(dir / name, text);
  return io_error_of(dir / name);
}

//! Expect `message` to contain each of `parts`.
void expect_mentions(const std::string& message, std::initializer_list<std::string> parts)
{
  for (const auto& part : parts)
    EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' missing from: " << message;
}

const std::string tetrahedron_off = "OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 2 0 3\n";

TEST(ReadErrors, missing_file_directory_and_unknown_extension_are_named)
{
  test::TempDir dir;
  const auto missing = dir / "missing.off";
  expect_mentions(io_error_of(missing), {missing.string(), "no such file"});
  std::filesystem::create_directory(dir / "folder.obj");
  expect_mentions(io_error_of(dir / "folder.obj"), {"directory"});
  test::write_file(dir / "mesh.vtk", tetrahedron_off);
  expect_mentions(io_error_of(dir / "mesh.vtk"), {"mesh.vtk", "unknown mesh format"});
  EXPECT_THROW(read_mesh(missing), IoError);
}

TEST(ReadErrors, bad_number_names_file_line_and_token)
{
  test::TempDir dir;
  std::string text = tetrahedron_off;
  text.replace(text.find("1 0 0\n"), 5, "1 0x 0");
  expect_mentions(io_error_of_text(dir, "bad.off", text), {"bad.off:4:", "vertex 1", "'0x'"});
  expect_mentions(io_error_of_text(dir, "bad.obj", "v 0 0 0\nv 1 zero 0\n"), {"bad.obj:2:", "vertex 1", "'zero'"});
  expect_mentions(io_error_of_text(dir, "bad.ply",
                               "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                               "property float z\nend_header\n0 1 one\n"), {"bad.ply:8:", "vertex 0", "'one'"});
  expect_mentions(io_error_of_text(dir, "bad.stl",
                               "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 z\n"), {"bad.stl:6:", "facet 0", "'z'"});
}

TEST(ReadErrors, wrong_off_counts_are_reported)
{
  test::TempDir dir;
  std::string fewer_faces = tetrahedron_off;
  fewer_faces.replace(fewer_faces.find("4 4 6"), 5, "4 3 6");
  expect_mentions(io_error_of_text(dir, "fewer.off", fewer_faces), {"fewer.off:10:", "unexpected content", "counts"});
  std::string more_faces = tetrahedron_off;
  more_faces.replace(more_faces.find("4 4 6"), 5, "4 5 6");
  expect_mentions(io_error_of_text(dir, "more.off", more_faces), {"more.off:", "4 of the 5 faces"});
  // One vertex too many announced: the face line is taken for the last vertex, and faces run out.
  expect_mentions(io_error_of_text(dir, "vertices.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
                  {"vertices.off:6:", "0 of the 1 faces"});
  expect_mentions(io_error_of_text(dir, "short.off", "OFF\n3 1 0\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n"),
                  {"short.off:4:", "vertex 1", "3 coordinates"});
  expect_mentions(io_error_of_text(dir, "counts.off", "OFF\nfour 4 6\n"), {"counts.off:2:", "counts"});
}

TEST(ReadErrors, malformed_records_of_each_format)
{
  test::TempDir dir;
  expect_mentions(io_error_of_text(dir, "zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"), {"zero.obj:4:", "face 0", "start at 1"});
  expect_mentions(io_error_of_text(dir, "two.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n"), {"two.obj:3:", "at least 3"});
  expect_mentions(io_error_of_text(dir, "magic.ply", "plx\n"), {"magic.ply:1:", "'ply'"});
  expect_mentions(io_error_of_text(dir, "format.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n"), {"format.ply:2:", "binary_middle_endian"});
  expect_mentions(io_error_of_text(dir, "noxyz.ply",
                               "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n"), {"noxyz.ply", "'z'"});
  expect_mentions(io_error_of_text(dir, "list.ply",
                               "ply\nformat ascii 1.0\nelement face 1\nproperty list float int vertex_indices\nend_header\n"), {"list.ply:4:", "not an integer type"});
  expect_mentions(io_error_of_text(dir, "loop.stl", "solid s\nfacet normal 0 0 1\nvertex 0 0 0\n"), {"loop.stl:3:", "facet 0", "'outer'"});
  expect_mentions(io_error_of_text(dir, "tiny.stl", "abc"), {"tiny.stl", "too few"});
}

//! Every format and encoding, written from a torus, then cut at several places.
struct Encoded {
  std::string extension;
  Encoding encoding;
};

TEST(ReadErrors, truncated_files_throw_io_error)
{
  test::TempDir dir;
  const Mesh torus = analytic::torus(10, 6, 1.0, 0.3);
  for (const Encoded& e : {Encoded{"off", Encoding::ascii}, Encoded{"ply", Encoding::ascii},
                          Encoded{"ply", Encoding::binary}, Encoded{"stl", Encoding::ascii},
                          Encoded{"stl", Encoding::binary}}) {
    const std::string name = "full_" + std::string(e.encoding == Encoding::binary ? "binary." : "ascii.") + e.extension;
    write_mesh(torus, dir / name, {.encoding = e.encoding});
    const std::string bytes = test::read_file(dir / name);
    // Cuts through the header, the vertices and the faces (before the last line, which a cut
    // in a text file could shorten into another valid line).
    for (const double fraction : {0.0, 0.001, 0.01, 0.05, 0.2, 0.5, 0.8, 0.95}) {
      const auto size = static_cast<std::size_t>(fraction * static_cast<double>(bytes.size()));
      SCOPED_TRACE(name + " cut to " + std::to_string(size) + " bytes");
      const auto cut = dir / ("cut." + e.extension);
      test::write_file(cut, bytes.substr(0, size));
      EXPECT_THROW(read_polygon_soup(cut), IoError);
    }
    // Binary files also notice a single missing byte.
    if (e.encoding == Encoding::binary) {
      test::write_file(dir / ("cut." + e.extension), bytes.substr(0, bytes.size() - 1));
      EXPECT_THROW(read_polygon_soup(dir / ("cut." + e.extension)), IoError) << name << " minus one byte";
    }
  }
}

TEST(ReadErrors, truncated_binary_files_name_the_element)
{
  test::TempDir dir;
  const Mesh sphere = analytic::icosphere(1); // 42 vertices, 80 triangles
  write_mesh(sphere, dir / "full.ply", {.encoding = Encoding::binary});
  write_mesh(sphere, dir / "full.stl", {.encoding = Encoding::binary});
  const std::string ply = test::read_file(dir / "full.ply"), stl = test::read_file(dir / "full.stl");
  // PLY faces take 1 + 3·4 bytes each: cutting 20 bytes leaves face 78 incomplete.
  test::write_file(dir / "cut.ply", ply.substr(0, ply.size() - 20));
  expect_mentions(io_error_of(dir / "cut.ply"), {"cut.ply: ", "face 78 of 80", "truncated"});
  // Cutting into the vertices: 42 vertices of 24 bytes follow the header.
  const std::size_t header = ply.find("end_header\n") + 11;
  test::write_file(dir / "early.ply", ply.substr(0, header + 24 * 10 + 5));
  expect_mentions(io_error_of(dir / "early.ply"), {"vertex 10 of 42"});
  // STL triangles take 50 bytes: cutting 60 leaves triangle 78 incomplete.
  test::write_file(dir / "cut.stl", stl.substr(0, stl.size() - 60));
  expect_mentions(io_error_of(dir / "cut.stl"), {"cut.stl: ", "triangle 78 of the 80", "truncated"});
}

TEST(ReadErrors, truncated_obj_records_throw_io_error)
{
  // OBJ has no counts: a cut at a line end is a valid shorter file, but a cut record is caught.
  test::TempDir dir;
  expect_mentions(io_error_of_text(dir, "cut_vertex.obj", "v 0 0 0\nv 1 0 0\nv 0 1"), {"cut_vertex.obj:3:", "vertex 2"});
  expect_mentions(io_error_of_text(dir, "cut_face.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2"), {"cut_face.obj:4:", "face 0"});
  expect_mentions(io_error_of_text(dir, "cut_slash.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/1 /"), {"cut_slash.obj:4:", "face 0"});
}

TEST(ReadErrors, huge_counts_do_not_allocate_before_failing)
{
  test::TempDir dir;
  expect_mentions(io_error_of_text(dir, "huge.off", "OFF\n4000000000000 1 0\n0 0 0\n"), {"vertices"});
  expect_mentions(io_error_of_text(dir, "huge.ply",
                               "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000000\nproperty float x\n"
                               "property float y\nproperty float z\nend_header\n"), {"truncated"});
  std::string list = "ply\nformat binary_little_endian 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
                     "property float z\nelement face 1\nproperty list uint int vertex_indices\nend_header\n";
  list += std::string("\xff\xff\xff\x7f", 4);
  expect_mentions(io_error_of_text(dir, "list.ply", list), {"face 0 of 1", "more than the rest of the file holds"});
}

} // namespace
} // namespace sdflow
