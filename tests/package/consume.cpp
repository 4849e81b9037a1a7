//! \file consume.cpp
//! \brief A program outside the project that uses sdflow as a library (scripts/test-package.sh):
//! exits 0 only if every check holds. The checks reach every dependency the static library links
//! privately (CHOLMOD, TetGen, muparser, oneTBB), so a package that forgets one fails to link.

#include <sdflow/check/tetgen_volume.h>
#include <sdflow/flow/scheme.h>
#include <sdflow/geometry/measures.h>
#include <sdflow/io/io.h>
#include <sdflow/shapes/expression.h>
#include <sdflow/shapes/mesher.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <unistd.h>

namespace {

int failures = 0;

//! Report `what` with its value and expected value; count it as failed unless within `tolerance`
//! (relative to |expected|).
void expect_near(const char* what, double value, double expected, double tolerance)
{
  const bool ok = std::abs(value - expected) <= tolerance * std::abs(expected);
  std::printf("%s %s: %.17g (expected %.17g)\n", ok ? "ok  " : "FAIL", what, value, expected);
  failures += !ok;
}

//! Report a condition; count it as failed if false.
void expect(const char* what, bool condition)
{
  std::printf("%s %s\n", condition ? "ok  " : "FAIL", what);
  failures += !condition;
}

//! The octahedron |x| + |y| + |z| = 1 as OFF text, every face listed clockwise (normals inward).
const char* const kInwardOctahedron = R"(OFF
6 8 0
1 0 0
-1 0 0
0 1 0
0 -1 0
0 0 1
0 0 -1
3 0 4 2
3 2 4 1
3 1 4 3
3 3 4 0
3 0 2 5
3 2 1 5
3 1 3 5
3 3 0 5
)";

void run_checks(const std::filesystem::path& dir)
{
  // Reading: validated and turned outward; eight equilateral faces of edge √2: area 4√3, volume 4/3.
  const auto off = dir / "octahedron.off";
  std::ofstream(off) << kInwardOctahedron;
  const sdflow::BuiltMesh in = sdflow::read_mesh(off);
  expect("read_mesh flips the inward octahedron",
         std::any_of(in.findings.begin(), in.findings.end(),
                     [](const sdflow::Finding& f) { return f.code == "orientation-flipped"; }));
  expect_near("octahedron volume", sdflow::enclosed_volume(in.mesh), 4.0 / 3.0, 1e-14);
  expect_near("octahedron area", sdflow::surface_area(in.mesh), 4 * std::sqrt(3.0), 1e-14);

  // Writing and reading back binary PLY keeps every coordinate.
  const auto ply = dir / "octahedron.ply";
  sdflow::write_mesh(in.mesh, ply, {.encoding = sdflow::Encoding::binary});
  const double ply_volume = sdflow::enclosed_volume(sdflow::read_mesh(ply).mesh);
  expect_near("PLY round trip volume", ply_volume, 4.0 / 3.0, 1e-14);

  // TetGen's tetrahedralisation of the octahedron sums to the same volume.
  const auto tetgen = sdflow::tetgen_volume_check(in.mesh);
  expect("one closed component for TetGen", tetgen.size() == 1);
  if (!tetgen.empty())
    expect_near("TetGen volume", tetgen[0].tetgen_volume, 4.0 / 3.0, 1e-12);

  // A formula (muparser) meshed (the remesher runs on oneTBB): the ellipsoid with semi-axes 2, 1, 1.
  const auto ellipsoid = sdflow::expression_surface(
      {.expression = "x^2/4 + y^2 + z^2 - 1",
       .box = Eigen::AlignedBox3d(Eigen::Vector3d(-2.5, -1.5, -1.5), Eigen::Vector3d(2.5, 1.5, 1.5))});
  const sdflow::Mesh mesh = sdflow::mesh_implicit_surface(ellipsoid, {.vertices = 500}).mesh;
  const double volume = sdflow::enclosed_volume(mesh);
  const double area = sdflow::surface_area(mesh);
  expect_near("meshed ellipsoid volume", volume, 8 * std::numbers::pi / 3, 0.03);

  // One step of the flow (CHOLMOD): surface diffusion keeps the volume and shrinks the area.
  sdflow::Mesh stepped = mesh;
  sdflow::set_vertex_positions(stepped, sdflow::flow_step(mesh, 1e-3).positions);
  expect_near("volume after a flow step", sdflow::enclosed_volume(stepped), volume, 1e-3);
  const double stepped_area = sdflow::surface_area(stepped);
  std::printf("     area %.6f -> %.6f\n", area, stepped_area);
  expect("a flow step shrinks the area", stepped_area < area * (1 - 1e-6));
}

} // namespace

int main()
{
  const auto dir = std::filesystem::temp_directory_path() / ("sdflow-consume-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  try {
    run_checks(dir);
  } catch (const std::exception& e) {
    std::printf("FAIL exception: %s\n", e.what());
    ++failures;
  }
  std::filesystem::remove_all(dir);
  std::printf("%s: %d check(s) failed\n", failures ? "FAIL" : "ok", failures);
  return failures ? 1 : 0;
}
