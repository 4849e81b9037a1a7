//! A write either replaces the file completely or leaves it as it was, with no temporary left.

#include "io/temp_dir.h"
#include "support/analytic_meshes.h"

#include "sdflow/io/io.h"

#include <gtest/gtest.h>

#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace sdflow {
namespace {

std::vector<std::string> entries(const std::filesystem::path& dir)
{
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(WriteAtomically, replaces_the_file_and_leaves_no_temporary)
{
  test::TempDir dir;
  const auto file = dir / "out.txt";
  test::write_file(file, "old");
  write_atomically(file, [](std::ostream& out) { out << "new content"; });
  EXPECT_EQ(test::read_file(file), "new content");
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"out.txt"});
}

TEST(WriteAtomically, throwing_writer_leaves_old_file_and_no_temporary)
{
  test::TempDir dir;
  const auto file = dir / "out.off";
  test::write_file(file, "old");
  EXPECT_THROW(write_atomically(file,
                                [](std::ostream& out) {
                                  out << "half a mesh";
                                  throw std::runtime_error("interrupted");
                                }),
               std::runtime_error);
  EXPECT_EQ(test::read_file(file), "old");
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"out.off"});
}

TEST(WriteAtomically, stream_failure_is_an_io_error_and_leaves_old_file)
{
  test::TempDir dir;
  const auto file = dir / "out.off";
  test::write_file(file, "old");
  EXPECT_THROW(write_atomically(file, [](std::ostream& out) { out.setstate(std::ios::badbit); }), IoError);
  EXPECT_EQ(test::read_file(file), "old");
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"out.off"});
}

TEST(WriteAtomically, missing_directory_is_an_io_error_naming_the_file)
{
  test::TempDir dir;
  const auto file = dir / "no" / "such" / "out.off";
  try {
    write_mesh(analytic::icosphere(0), file);
    ADD_FAILURE() << "no exception";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
  }
  EXPECT_TRUE(entries(dir.path()).empty());
}

TEST(WriteAtomically, unknown_extension_writes_nothing)
{
  test::TempDir dir;
  EXPECT_THROW(write_mesh(analytic::icosphere(0), dir / "mesh.vtk"), IoError);
  EXPECT_TRUE(entries(dir.path()).empty());
}

} // namespace
} // namespace sdflow
