//! `sdflow repair` end to end on damaged files (seams of duplicate vertices, flipped, repeated
//! faces, isolated vertices, a non-manifold fin, a CAD-like STL soup): the output passes `stats`,
//! keeps the volume, every repair is reported by code with its count; the verbs that work on
//! faces accept the damaged file, and `stats` and `run` point to `repair`; small files made the way
//! viewers, OBJ exporters and scanners damage theirs are repaired too.
#include "sdflow/io/io.h"
#include "support/analytic_meshes.h"
#include "support/run_command.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <cmath>
#include <map>
#include <regex>
#include <sstream>

namespace sdflow {
namespace {

namespace fs = std::filesystem;

//! Volumes of the same triangles summed in another order, through 17-digit text.
constexpr double volume_tolerance = 1e-12;

//! An OFF file of points and triangles, written as given (no validation).
void write_off(const fs::path& file, const std::vector<Eigen::Vector3d>& points,
               const std::vector<std::array<long long, 3>>& triangles)
{
  std::ofstream out(file);
  out.precision(17);
  out << "OFF\n" << points.size() << ' ' << triangles.size() << " 0\n";
  for (const auto& p : points)
    out << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  for (const auto& t : triangles)
    out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
}

//! The number after the first `"key" : ` of a JSON text (NaN when there is none).
double json_number(const std::string& json, const std::string& key)
{
  std::smatch m;
  if (!std::regex_search(json, m, std::regex("\"" + key + "\" : (-?[0-9][0-9.eE+-]*)")))
    return std::nan("");
  return std::stod(m[1]);
}

//! The number of a key of the JSON object itself, not of an object nested in it (toml++ indents
//! the object's own keys by four spaces; NaN when there is none).
double top_level_number(const std::string& json, const std::string& key)
{
  std::smatch m;
  if (!std::regex_search(json, m, std::regex("\n    \"" + key + "\" : (-?[0-9][0-9.eE+-]*)")))
    return std::nan("");
  return std::stod(m[1]);
}

//! The repairs of a `repair --json` object, as code → count (its entries are {code, count, message}).
std::map<std::string, long long> repair_counts(const std::string& json)
{
  std::map<std::string, long long> counts;
  const std::regex entry("\"code\" : \"([a-z-]+)\",\\s*\"count\" : ([0-9]+)");
  for (auto it = std::sregex_iterator(json.begin(), json.end(), entry); it != std::sregex_iterator(); ++it)
    counts[(*it)[1]] = std::stoll((*it)[2]);
  return counts;
}

class RepairCommand : public ::testing::Test {
protected:
  fs::path dir = fs::temp_directory_path() / ("sdflow_repair_" + std::to_string(::getpid()));
  Mesh sphere = analytic::icosphere(2);
  double volume = 0;
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<long long, 3>> triangles;

  void SetUp() override
  {
    fs::create_directories(dir);
    for (auto v : sphere.vertices())
      points.push_back(to_eigen(sphere.point(v)));
    for (auto f : sphere.faces()) {
      std::array<long long, 3> t{};
      int k = 0;
      for (auto v : f.vertices())
        t[k++] = v.idx();
      triangles.push_back(t);
    }
    write_mesh(sphere, dir / "sphere.off");
    volume = json_number(output_of("stats --json --no-tetgen " + (dir / "sphere.off").string()), "volume");
  }
  void TearDown() override { fs::remove_all(dir); }

  //! The output of a verb that must succeed (stdout only).
  static std::string output_of(const std::string& arguments)
  {
    const auto r = analytic::run_sdflow(arguments + " 2>/dev/null");
    EXPECT_EQ(r.exit_code, 0) << arguments << "\n" << r.output;
    return r.output;
  }

  //! The sphere damaged as an exported OFF often is: the vertices with x > 0.5 repeated (the faces
  //! of even index use the copies, a seam), 3 faces flipped, one repeated, two vertices of no face.
  fs::path damaged_sphere()
  {
    std::map<long long, long long> copy;
    const auto n = static_cast<long long>(points.size());
    for (long long i = 0; i < n; ++i)
      if (points[i].x() > 0.5) {
        copy[i] = static_cast<long long>(points.size());
        points.push_back(points[i]);
      }
    for (std::size_t f = 0; f < triangles.size(); f += 2)
      for (long long& i : triangles[f])
        if (copy.contains(i))
          i = copy[i];
    // A vertex whose faces all took the copy is left without a face; one used on both sides is merged.
    std::vector<bool> used(points.size(), false);
    for (const auto& t : triangles)
      for (const long long i : t)
        used[i] = true;
    for (const auto& [original, twin] : copy)
      duplicates += used[original] && used[twin];
    unused = copy.size() - duplicates;
    for (const int f : {2, 50, 140})
      std::swap(triangles[f][1], triangles[f][2]);
    triangles.push_back(triangles[10]);
    points.push_back({4, 4, 4});
    points.push_back({5, 4, 4});
    write_off(dir / "damaged.off", points, triangles);
    return dir / "damaged.off";
  }
  std::size_t duplicates = 0; //!< seam vertices used on both sides
  std::size_t unused = 0;     //!< seam vertices whose faces all took the copy
};

TEST_F(RepairCommand, a_damaged_sphere_is_repaired_into_one_stats_accepts)
{
  const fs::path in = damaged_sphere();
  const auto refused = analytic::run_sdflow("stats " + in.string());
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("sdflow repair " + in.string() + " -o " + (dir / "damaged_repaired.off").string()),
            std::string::npos)
    << refused.output;

  const fs::path out = dir / "repaired.off";
  const std::string json = output_of("repair --json " + in.string() + " -o " + out.string());
  const auto counts = repair_counts(json);
  ASSERT_EQ(counts.size(), 4u) << json;
  EXPECT_EQ(counts.at("duplicate-vertex"), static_cast<long long>(duplicates)) << json;
  EXPECT_EQ(counts.at("inconsistent-orientation"), 3) << json;
  EXPECT_EQ(counts.at("repeated-face"), 1) << json;
  EXPECT_GT(duplicates, 0u);
  EXPECT_EQ(counts.at("isolated-vertex"), static_cast<long long>(2 + unused)) << json;
  for (const char* key : {"input", "output", "input_vertices", "input_faces", "vertices", "faces", "repairs", "findings",
                          "untangled_vertices", "retriangulation_passes", "self_intersecting_pairs"})
    EXPECT_NE(json.find(std::string("\"") + key + "\" : "), std::string::npos) << key;
  EXPECT_EQ(json_number(json, "vertices"), static_cast<double>(sphere.n_vertices()));
  EXPECT_EQ(json_number(json, "faces"), static_cast<double>(sphere.n_faces()));
  EXPECT_EQ(json_number(json, "self_intersecting_pairs"), 0);

  const std::string stats = output_of("stats --json --no-tetgen " + out.string());
  EXPECT_NEAR(json_number(stats, "volume"), volume, volume_tolerance * volume);
  EXPECT_EQ(json_number(stats, "genus"), 0);

  const auto text = analytic::run_sdflow("repair " + in.string() + " -o " + out.string());
  EXPECT_EQ(text.exit_code, 0) << text.output;
  EXPECT_NE(text.output.find("[duplicate-vertex] "), std::string::npos) << text.output;
  EXPECT_NE(text.output.find("wrote " + out.string()), std::string::npos) << text.output;
}

TEST_F(RepairCommand, verbs_that_work_on_faces_accept_the_damaged_file)
{
  const fs::path in = damaged_sphere();
  const std::string pairs = output_of("intersections --json " + in.string());
  EXPECT_EQ(json_number(pairs, "faces"), static_cast<double>(triangles.size()));
  EXPECT_EQ(json_number(pairs, "intersecting_pairs"), 1) << "the repeated face and its original: " << pairs;

  const auto components = analytic::run_sdflow("components " + in.string() + " -o " + (dir / "kept.off").string());
  EXPECT_EQ(components.exit_code, 0) << components.output;
  EXPECT_NE(components.output.find("not a valid mesh"), std::string::npos) << components.output;
  EXPECT_TRUE(fs::exists(dir / "kept.off"));

  const auto retri = analytic::run_sdflow("retriangulate " + in.string() + " -o " + (dir / "retri.ply").string());
  EXPECT_EQ(retri.exit_code, 0) << retri.output;
}

TEST_F(RepairCommand, run_suggests_repair_and_applies_it_when_asked)
{
  const fs::path in = damaged_sphere();
  const auto refused = analytic::run_sdflow("run --input " + in.string() + " --out " + (dir / "run1").string() +
                                            " --steps 1 --quiet");
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("sdflow repair"), std::string::npos) << refused.output;

  const auto repaired = analytic::run_sdflow("run --input " + in.string() + " --out " + (dir / "run2").string() +
                                             " --steps 1 --quiet --repair");
  ASSERT_EQ(repaired.exit_code, 0) << repaired.output;
  std::ifstream settings(dir / "run2" / "run.toml");
  std::stringstream text;
  text << settings.rdbuf();
  EXPECT_NE(text.str().find("repair = true"), std::string::npos) << text.str();
}

TEST_F(RepairCommand, a_cad_like_stl_soup_closes_with_a_merge_tolerance)
{
  // Every triangle with its own corners, rounded apart by up to 2e-9 as a CAD export's may be.
  std::ofstream stl(dir / "cad.stl");
  stl.precision(17);
  stl << "solid cad\n";
  int corner = 0;
  for (const auto& t : triangles) {
    stl << "facet normal 0 0 0\nouter loop\n";
    for (const long long i : t) {
      const Eigen::Vector3d p = points[i] + Eigen::Vector3d(1e-9 * (corner++ % 3), 0, 0);
      stl << "vertex " << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
    }
    stl << "endloop\nendfacet\n";
  }
  stl << "endsolid cad\n";
  stl.close();
  const std::string json =
    output_of("repair --json --merge-tolerance 1e-6 " + (dir / "cad.stl").string() + " -o " + (dir / "cad.off").string());
  EXPECT_EQ(json_number(json, "vertices"), static_cast<double>(sphere.n_vertices())) << json;
  const std::string stats = output_of("stats --json --no-tetgen " + (dir / "cad.off").string());
  EXPECT_EQ(json_number(stats, "boundary_loops"), 0) << stats;
  EXPECT_NEAR(json_number(stats, "volume"), volume, 1e-7);
}

TEST_F(RepairCommand, remove_self_intersections_leaves_none)
{
  // The damaged sphere with its cap above z = 0.2 folded down through the rest.
  damaged_sphere();
  for (auto& p : points)
    if (p.z() > 0.2)
      p.z() = 0.2 - 2.2 * (p.z() - 0.2);
  write_off(dir / "folded.off", points, triangles);
  const std::string plain = output_of("repair --json " + (dir / "folded.off").string() + " -o " + (dir / "a.off").string());
  EXPECT_GT(json_number(plain, "self_intersecting_pairs"), 0) << plain;
  EXPECT_EQ(json_number(plain, "retriangulation_passes"), 0) << plain;
  EXPECT_EQ(json_number(plain, "untangled_vertices"), 0) << plain;

  const std::string clean = output_of("repair --json --remove-self-intersections " + (dir / "folded.off").string() +
                                      " -o " + (dir / "b.off").string());
  EXPECT_EQ(json_number(clean, "self_intersecting_pairs"), 0) << clean;
  // Undone by moving vertices, or by re-triangulating what the moves left.
  EXPECT_GE(json_number(clean, "untangled_vertices") + json_number(clean, "retriangulation_passes"), 1) << clean;
  const std::string stats = output_of("stats --json " + (dir / "b.off").string());
  EXPECT_EQ(json_number(stats, "self_intersecting_pairs"), 0) << stats;
}

//! A file of tests/data/damaged/ (make_damaged.py says how each was made and which origin it mimics).
std::string damaged_file(const std::string& name) { return std::string(SDFLOW_SOURCE_DIR) + "/tests/data/damaged/" + name; }

//! Each damaged file of another origin: `stats` refuses it, `repair` fixes it with exactly the repairs
//! its damage calls for, and the repaired file passes `stats` with the shape the file describes.
struct OriginCase {
  std::string file;
  std::map<std::string, long long> repairs;
  double vertices, faces, components, boundary_loops, volume;
};

TEST_F(RepairCommand, meshes_of_other_origins_are_repaired)
{
  // The UV sphere's trapezoids are planar, so its volume does not depend on how they are split:
  // the polyhedron's (4π/3 = 4.19 for the sphere itself); a seam left open would bound none.
  const std::vector<OriginCase> cases{
      {"quad-cube-mixed-winding.off", {{"polygon-triangulated", 6}, {"inconsistent-orientation", 4}}, 8, 12, 1, 0, 1.0},
      {"tetrahedra-sharing-a-corner.off", {{"non-manifold-vertex", 1}}, 8, 8, 2, 0, 1.5},
      {"uv-sphere-seams.obj", {{"duplicate-vertex", 7 + 2 * 11}, {"polygon-triangulated", 72}}, 7 * 12 + 2, 168, 1, 0,
       3.8477590650},
      {"scan-patch.ply", {{"duplicate-vertex", 10}, {"zero-area-face", 1}}, 101, 161, 1, 2, 0.0},
  };
  for (const OriginCase& c : cases) {
    SCOPED_TRACE(c.file);
    const std::string in = damaged_file(c.file);
    const auto refused = analytic::run_sdflow("stats --no-tetgen " + in);
    EXPECT_EQ(refused.exit_code, 2) << refused.output;
    EXPECT_NE(refused.output.find("sdflow repair"), std::string::npos) << refused.output;

    const fs::path out = dir / ("repaired_" + fs::path(c.file).stem().string() + ".ply");
    const std::string json = output_of("repair --json " + in + " -o " + out.string());
    EXPECT_EQ(repair_counts(json), c.repairs) << json;
    EXPECT_EQ(json_number(json, "vertices"), c.vertices) << json;
    EXPECT_EQ(json_number(json, "faces"), c.faces) << json;

    const std::string stats = output_of("stats --json " + out.string());
    EXPECT_EQ(json_number(stats, "component_count"), c.components) << stats;
    EXPECT_EQ(json_number(stats, "boundary_loops"), c.boundary_loops) << stats;
    EXPECT_EQ(json_number(stats, "self_intersecting_pairs"), 0) << stats;
    // The split corner moves each copy 1e-6 of the way into its fan: volumes change by about that.
    EXPECT_NEAR(top_level_number(stats, "volume"), c.volume, 1e-5 * std::max(1.0, c.volume)) << stats;
  }

  // A run straight from the exporter's file, repaired on the way in.
  const auto run = analytic::run_sdflow("run --input " + damaged_file("uv-sphere-seams.obj") + " --out " +
                                        (dir / "uv-run").string() + " --steps 2 --quiet --repair");
  EXPECT_EQ(run.exit_code, 0) << run.output;
}

TEST_F(RepairCommand, an_unrepairable_file_is_refused_with_exit_code_two)
{
  std::ofstream(dir / "broken.off") << "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n";
  const auto r = analytic::run_sdflow("repair " + (dir / "broken.off").string() + " -o " + (dir / "x.off").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("face 0 uses vertex 7"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "x.off"));
}

} // namespace
} // namespace sdflow
