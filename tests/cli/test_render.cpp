//! `sdflow render` end to end: PNGs of the requested size for closed surfaces and a surface with
//! boundary, and clear refusals (bad options, missing input, gnuplot missing or failing) that leave
//! no file behind. Pixel colours are not asserted.
#include "io/temp_dir.h"
#include "sdflow/io/io.h"
#include "support/analytic_meshes.h"
#include "support/run_command.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

namespace sdflow {
namespace {

namespace fs = std::filesystem;

struct PngSize {
  std::uint32_t width = 0, height = 0;
};

//! Width and height from the IHDR chunk, if the file starts with the PNG signature and IHDR.
std::optional<PngSize> png_size(const fs::path& file)
{
  const std::string bytes = test::read_file(file);
  const std::string signature = "\x89PNG\r\n\x1a\n";
  if (bytes.size() < 24 || bytes.compare(0, 8, signature) != 0 || bytes.compare(12, 4, "IHDR") != 0)
    return std::nullopt;
  auto big_endian = [&](std::size_t at) {
    std::uint32_t value = 0;
    for (std::size_t i = 0; i < 4; ++i)
      value = value << 8 | static_cast<unsigned char>(bytes[at + i]);
    return value;
  };
  return PngSize{big_endian(16), big_endian(20)};
}

//! Names in a folder, to check that a refused render leaves nothing (not even a temporary) behind.
std::size_t entries(const fs::path& folder)
{
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(folder), fs::directory_iterator()));
}

TEST(RenderCommand, closed_surfaces_give_pngs_of_the_requested_size)
{
  const test::TempDir dir;
  write_mesh(analytic::icosphere(3, 1.0), dir / "sphere.off");
  write_mesh(analytic::torus(48, 24, 2.0, 0.8), dir / "torus.ply", {.encoding = Encoding::binary});
  struct Case {
    std::string mesh, options;
    PngSize size;
  };
  for (const Case& c : {Case{"sphere.off", "", {800, 600}},
                        Case{"sphere.off", "--size 321,203 --colour none --view 90,0", {321, 203}},
                        Case{"torus.ply", "--size 640,480 --title \"torus_1 'before'\"", {640, 480}},
                        Case{"torus.ply", "--size 500,500 --view 0,-45 --colour none", {500, 500}},
                        // Too narrow for the colour scale's strip: coloured, without the scale.
                        Case{"torus.ply", "--size 64,48", {64, 48}}}) {
    SCOPED_TRACE(c.mesh + " " + c.options);
    const fs::path out = dir / "picture.png";
    fs::remove(out);
    const auto r = analytic::run_sdflow("render " + (dir / c.mesh).string() + " -o " + out.string() + " " + c.options);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto size = png_size(out);
    ASSERT_TRUE(size.has_value()) << out << " is not a PNG";
    EXPECT_EQ(size->width, c.size.width);
    EXPECT_EQ(size->height, c.size.height);
  }
  EXPECT_EQ(entries(dir.path()), 3u) << "a temporary file was left beside the picture";
}

TEST(RenderCommand, surface_with_boundary_renders_from_either_side)
{
  const test::TempDir dir;
  write_mesh(analytic::disk(8, 1.0), dir / "disk.obj");
  for (const std::string view : {"60,30", "120,30"}) {
    SCOPED_TRACE(view);
    const fs::path out = dir / "disk.png";
    fs::remove(out);
    const auto r = analytic::run_sdflow("render " + (dir / "disk.obj").string() + " -o " + out.string() +
                                        " --size 200,150 --view " + view);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto size = png_size(out);
    ASSERT_TRUE(size.has_value());
    EXPECT_EQ(size->width, 200u);
    EXPECT_EQ(size->height, 150u);
  }
}

TEST(RenderCommand, missing_input_fails_without_output)
{
  const test::TempDir dir;
  const fs::path out = dir / "none.png";
  const auto r = analytic::run_sdflow("render " + (dir / "absent.off").string() + " -o " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("absent.off"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(entries(dir.path()), 0u);
}

TEST(RenderCommand, bad_options_are_refused_without_output)
{
  const test::TempDir dir;
  write_mesh(analytic::icosphere(2, 1.0), dir / "sphere.off");
  const std::string mesh = (dir / "sphere.off").string();
  const fs::path out = dir / "picture.png";
  for (const std::string options : {"--view 60", "--view 60,abc", "--view inf,30", "--view 60,30,10", "--size 0,100",
                                    "--size 640", "--colour rainbow"}) {
    SCOPED_TRACE(options);
    const auto r = analytic::run_sdflow("render " + mesh + " -o " + out.string() + " " + options);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_FALSE(fs::exists(out));
  }
  const auto r = analytic::run_sdflow("render " + mesh + " -o " + (dir / "picture.jpg").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(".png"), std::string::npos) << r.output;
  EXPECT_EQ(entries(dir.path()), 1u);
}

//! Runs the command with PATH replaced by `path`, then restores it.
analytic::CommandResult run_with_path(const std::string& path, const std::string& arguments)
{
  const char* saved = std::getenv("PATH");
  const std::string original = saved ? saved : "";
  ::setenv("PATH", path.c_str(), 1);
  const auto r = analytic::run_sdflow(arguments);
  ::setenv("PATH", original.c_str(), 1);
  return r;
}

TEST(RenderCommand, gnuplot_missing_or_failing_is_reported_without_output)
{
  const test::TempDir dir;
  write_mesh(analytic::icosphere(2, 1.0), dir / "sphere.off");
  const fs::path bin = dir / "bin", pictures = dir / "pictures";
  fs::create_directories(bin);
  fs::create_directories(pictures);
  const std::string arguments = "render " + (dir / "sphere.off").string() + " -o " + (pictures / "p.png").string();

  auto r = run_with_path(bin.string(), arguments);
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("cannot run gnuplot"), std::string::npos) << r.output;
  EXPECT_EQ(entries(pictures), 0u);

  test::write_file(bin / "gnuplot", "#!/bin/sh\necho 'line 3: simulated failure' >&2\nexit 1\n");
  fs::permissions(bin / "gnuplot", fs::perms::owner_all);
  r = run_with_path(bin.string(), arguments);
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("gnuplot failed"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("simulated failure"), std::string::npos) << r.output;
  EXPECT_EQ(entries(pictures), 0u);
}

} // namespace
} // namespace sdflow
