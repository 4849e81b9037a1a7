//! `sdflow stats MESH [--json]`: validation findings, topology, area, volume (divergence theorem and
//! TetGen), mean curvature deviation and mesh quality. JSON keys are documented in README.md.

#include "common_options.h"
#include "json_report.h"
#include "repair_hint.h"
#include "verbs.h"
#include "work_progress.h"

#include "sdflow/check/statistics.h"
#include "sdflow/io/io.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <cmath>
#include <iostream>
#include <string>

namespace sdflow::cli {
namespace {

struct StatsArguments {
  std::string mesh;
  bool json = false;
  bool no_tetgen = false;
};

toml::table histogram(const std::map<int, int>& counts)
{
  toml::table t;
  for (auto [valence, count] : counts)
    t.insert(std::to_string(valence), count);
  return t;
}

toml::table to_json_table(const std::string& file, const BuiltMesh& built, const MeshStatistics& s)
{
  toml::array findings = findings_json(built.findings);
  toml::array components;
  for (const ComponentStatistics& c : s.components) {
    toml::table t{{"vertices", c.topology.vertices},
                  {"edges", c.topology.edges},
                  {"faces", c.topology.faces},
                  {"euler_characteristic", c.topology.euler_characteristic},
                  {"genus", c.topology.genus},
                  {"boundary_loops", c.topology.boundary_loops},
                  {"closed", c.topology.closed()},
                  {"area", c.area},
                  {"volume", c.volume},
                  {"material_volume", c.material_volume}};
    if (c.tetgen_volume) {
      t.insert("tetgen_volume", *c.tetgen_volume);
      t.insert("tetrahedra", c.tetrahedra);
    }
    if (c.crossing_faces > 0)
      t.insert("crossing_faces", static_cast<int64_t>(c.crossing_faces));
    components.push_back(std::move(t));
  }
  const MeshQuality& q = s.quality;
  toml::table root{{"file", file},
                   {"findings", std::move(findings)},
                   {"vertices", s.vertices},
                   {"edges", s.edges},
                   {"faces", s.faces},
                   {"component_count", static_cast<int64_t>(s.components.size())},
                   {"components", std::move(components)},
                   {"genus", s.genus},
                   {"boundary_loops", s.boundary_loops},
                   {"area", s.area},
                   {"volume", s.volume},
                   {"material_volume", s.material_volume},
                   {"self_intersecting_pairs", static_cast<int64_t>(s.self_intersecting_pairs)},
                   {"mean_curvature", s.curvature.mean},
                   {"curvature_deviation", s.curvature.deviation},
                   {"quality",
                    toml::table{{"min_angle_deg", q.min_angle_deg},
                                {"max_angle_deg", q.max_angle_deg},
                                {"min_angle_p05_deg", q.min_angle_p05_deg},
                                {"obtuse_triangle_fraction", q.obtuse_triangle_fraction},
                                {"edge_length", toml::table{{"min", q.edge_min}, {"max", q.edge_max}, {"mean", q.edge_mean}, {"stddev", q.edge_stddev}}},
                                {"valence", histogram(q.valence_histogram)},
                                {"boundary_valence", histogram(q.boundary_valence_histogram)}}}};
  if (s.tetgen_volume)
    root.insert("tetgen_volume", *s.tetgen_volume);
  if (!s.tetgen_skipped.empty())
    root.insert("tetgen_skipped", s.tetgen_skipped);
  if (std::isfinite(s.curvature.deviation_pct))
    root.insert("curvature_deviation_pct", s.curvature.deviation_pct);
  return root;
}

void print_text(const std::string& file, const BuiltMesh& built, const MeshStatistics& s)
{
  std::cout << fmt::format("{}\n", file);
  for (const Finding& f : built.findings)
    std::cout << fmt::format("  {}: [{}] {}\n", severity_name(f.severity), f.code, f.message);
  std::cout << fmt::format("  {} vertices, {} edges, {} faces, {} component(s)\n", s.vertices, s.edges, s.faces, s.components.size());
  for (std::size_t i = 0; i < s.components.size(); ++i) {
    const ComponentStatistics& c = s.components[i];
    std::cout << fmt::format("  component {}: {} faces, genus {}, {} boundary loop(s), area {:.10g}", i, c.topology.faces,
                             c.topology.genus, c.topology.boundary_loops, c.area);
    if (c.topology.closed())
      std::cout << fmt::format(", volume {:.10g}", c.volume);
    else
      std::cout << fmt::format(", material volume {:.10g}", c.material_volume);
    if (c.tetgen_volume)
      std::cout << fmt::format(" (TetGen {:.10g}, {} tetrahedra)", *c.tetgen_volume, c.tetrahedra);
    if (c.crossing_faces > 0)
      std::cout << fmt::format("; {} face(s) in intersecting pairs", c.crossing_faces);
    std::cout << '\n';
  }
  std::cout << fmt::format("  area {:.10g}\n  volume {:.10g}", s.area, s.volume);
  if (s.tetgen_volume)
    std::cout << (s.volume != 0 ? fmt::format("  (TetGen {:.10g}, relative difference {:.2e})", *s.tetgen_volume,
                                              std::abs(*s.tetgen_volume - s.volume) / std::abs(s.volume))
                                : fmt::format("  (TetGen {:.10g}, difference {:.2e})", *s.tetgen_volume,
                                              std::abs(*s.tetgen_volume - s.volume)));
  if (!s.tetgen_skipped.empty())
    std::cout << fmt::format("  ({})", s.tetgen_skipped);
  if (s.boundary_loops > 0)
    std::cout << fmt::format("\n  material volume {:.10g} (each boundary loop closed by a flat cap, as a run measures it)",
                             s.material_volume);
  std::cout << fmt::format("\n  mean curvature H̃ {:.8g}, deviation H_dev {:.6g} ({})\n", s.curvature.mean,
                           s.curvature.deviation,
                           std::isfinite(s.curvature.deviation_pct) ? fmt::format("{:.4g}% of |H̃|", s.curvature.deviation_pct)
                                                                    : std::string("no relative deviation: H̃ = 0"));
  const MeshQuality& q = s.quality;
  std::cout << fmt::format("  angles {:.2f}°..{:.2f}° (5% of triangles below {:.2f}°), {:.2f}% obtuse\n", q.min_angle_deg,
                           q.max_angle_deg, q.min_angle_p05_deg, 100 * q.obtuse_triangle_fraction);
  std::cout << fmt::format("  edge length min {:.6g} max {:.6g} mean {:.6g} stddev {:.6g}\n", q.edge_min, q.edge_max,
                           q.edge_mean, q.edge_stddev);
  std::cout << "  valence";
  for (auto [valence, count] : q.valence_histogram)
    std::cout << fmt::format(" {}:{}", valence, count);
  if (!q.boundary_valence_histogram.empty()) {
    std::cout << "  boundary";
    for (auto [valence, count] : q.boundary_valence_histogram)
      std::cout << fmt::format(" {}:{}", valence, count);
  }
  std::cout << '\n';
}

} // namespace

void add_stats_verb(CLI::App& app)
{
  auto args = std::make_shared<StatsArguments>();
  CLI::App* verb = app.add_subcommand("stats", "Validate a mesh and report topology, area, volume, curvature and quality");
  verb->add_option("mesh", args->mesh, fmt::format("Mesh file ({})", mesh_formats))->required();
  add_json_flag(*verb, args->json);
  verb->add_flag("--no-tetgen", args->no_tetgen, "Skip the TetGen volume cross-check");
  verb->callback([args] {
    WorkProgress progress("stats");
    progress.stage("reading " + args->mesh);
    BuiltMesh built = read_mesh_or_suggest_repair(args->mesh);
    progress.stage(fmt::format("measuring {} faces", built.mesh.n_faces()));
    const MeshStatistics s = mesh_statistics(built.mesh, {.tetgen_check = !args->no_tetgen});
    progress.finish();
    if (s.self_intersecting_pairs > 0)
      built.findings.push_back(
          {Severity::warning, "self-intersection",
           fmt::format("{}: {} pair(s) of triangles intersect: the surface crosses itself (or its components cross "
                       "each other), so its volume is not that of a solid and which component is a body or a "
                       "cavity is not defined", args->mesh, s.self_intersecting_pairs)});
    if (args->json)
      print_json(to_json_table(args->mesh, built, s));
    else
      print_text(args->mesh, built, s);
  });
}

} // namespace sdflow::cli
