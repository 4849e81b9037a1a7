//! `sdflow repair IN -o OUT [--merge-tolerance F] [--remove-self-intersections] [--json]`: a
//! damaged mesh made valid (io/repair.h), each repair reported by the code of the finding it fixes;
//! with --remove-self-intersections, a surface that still crosses itself is untangled and, where
//! that is not enough, re-triangulated (retri/surface_repair.h). JSON keys are documented in README.md.

#include "common_options.h"
#include "verbs.h"
#include "work_progress.h"

#include "sdflow/io/io.h"
#include "sdflow/io/repair.h"
#include "sdflow/retri/surface_repair.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <iostream>
#include <memory>
#include <string>

namespace sdflow::cli {
namespace {

struct RepairArguments {
  std::string input;
  std::string output;
  RepairOptions options;
  bool remove_self_intersections = false;
  bool json = false;
  Encoding encoding = Encoding::binary;
};

//! What the verb did, for either report.
struct RepairReport {
  std::size_t input_vertices = 0, input_faces = 0;
  RepairedSurface surface;
};

void report_json(const RepairArguments& args, const RepairReport& r)
{
  toml::array repairs;
  for (const Repair& repair : r.surface.repaired.repairs)
    repairs.push_back(toml::table{{"code", repair.code}, {"count", static_cast<int64_t>(repair.count)},
                                  {"message", repair.message}});
  toml::array findings;
  for (const Finding& f : r.surface.repaired.findings)
    findings.push_back(toml::table{{"severity", severity_name(f.severity)}, {"code", f.code}, {"message", f.message}});
  const Mesh& mesh = r.surface.mesh();
  toml::table root{{"input", args.input},
                   {"output", args.output},
                   {"input_vertices", static_cast<int64_t>(r.input_vertices)},
                   {"input_faces", static_cast<int64_t>(r.input_faces)},
                   {"vertices", static_cast<int64_t>(mesh.n_vertices())},
                   {"faces", static_cast<int64_t>(mesh.n_faces())},
                   {"repairs", std::move(repairs)},
                   {"findings", std::move(findings)},
                   {"untangled_vertices", static_cast<int64_t>(untangled_vertices(r.surface))},
                   {"retriangulation_passes", static_cast<int64_t>(r.surface.resolved ? r.surface.resolved->summaries.size() : 0)},
                   {"self_intersecting_pairs", static_cast<int64_t>(r.surface.intersecting_pairs)}};
  std::cout << toml::json_formatter{root} << '\n';
}

void report_text(const RepairArguments& args, const RepairReport& r)
{
  const Mesh& mesh = r.surface.mesh();
  std::cout << fmt::format("{}: {} vertices, {} faces -> {} vertices, {} faces\n", args.input, r.input_vertices,
                           r.input_faces, mesh.n_vertices(), mesh.n_faces());
  if (r.surface.repaired.repairs.empty())
    std::cout << "  nothing to repair\n";
  for (const Repair& repair : r.surface.repaired.repairs)
    std::cout << fmt::format("  [{}] {}\n", repair.code, repair.message);
  for (const Finding& f : r.surface.repaired.findings)
    std::cout << fmt::format("  {}: [{}] {}\n", severity_name(f.severity), f.code, f.message);
  if (r.surface.resolved && r.surface.resolved->untangled) {
    const UntangleSummary& u = *r.surface.resolved->untangled;
    std::cout << fmt::format("  [self-intersection] {} crossing pair(s) undone by moving {} vertices (at most {:.2g} "
                             "mean edge lengths) in {} rounds\n",
                             u.pairs, u.moved_vertices, u.max_displacement, u.rounds);
  }
  if (r.surface.resolved)
    for (std::size_t pass = 0; pass < r.surface.resolved->summaries.size(); ++pass)
      std::cout << fmt::format("  [self-intersection] re-triangulation {}: {}\n", pass + 1, r.surface.resolved->summaries[pass]);
  if (r.surface.intersecting_pairs > 0)
    std::cout << fmt::format("  warning: [self-intersection] {} pair(s) of faces intersect{}\n", r.surface.intersecting_pairs,
                             args.remove_self_intersections ? "" : " (--remove-self-intersections re-triangulates them away)");
  std::cout << fmt::format("  wrote {}\n", args.output);
}

void run(const RepairArguments& args)
{
  format_from_extension(args.output); // refuse an unknown format before the work
  WorkProgress progress("repair");
  progress.stage("reading " + args.input);
  const PolygonSoup soup = read_polygon_soup(args.input);
  const RepairReport report{
      .input_vertices = soup.points.size(),
      .input_faces = soup.polygons.size(),
      .surface = repair_surface(soup, args.input, args.options, args.remove_self_intersections,
                                [&progress](const std::string& what) { progress.stage(what); })};
  progress.stage("writing " + args.output);
  const Mesh& repaired = report.surface.mesh();
  write_mesh(repaired, args.output, {.encoding = args.encoding, .vertex_fields = surface_fields(repaired)});
  progress.finish();
  if (args.json)
    report_json(args, report);
  else
    report_text(args, report);
}

} // namespace

void add_repair_verb(CLI::App& app)
{
  auto args = std::make_shared<RepairArguments>();
  CLI::App* verb = app.add_subcommand(
      "repair", "Make a damaged mesh valid: merge duplicate vertices, drop degenerate and repeated faces, split "
                "non-manifold edges and vertices, orient consistently and outward, drop isolated vertices");
  verb->add_option("input", args->input, fmt::format("Input mesh ({})", mesh_formats))->required();
  add_output_option(*verb, args->output, "Output mesh")->required();
  add_encoding_flags(*verb, args->encoding);
  verb->add_option("--merge-tolerance", args->options.merge_tolerance,
                   "Merge vertices closer than this fraction of the bounding-box diagonal, at most 0.1 "
                   "(default 0: only identical ones)")
      ->type_name("F")
      ->check(CLI::Range(0.0, 0.1).description(""));
  verb->add_flag("--remove-self-intersections", args->remove_self_intersections,
                 "Re-triangulate a surface that crosses itself until it does not (the pipeline of `sdflow "
                 "retriangulate` with its defaults, at most 5 passes)");
  add_json_flag(*verb, args->json, "the repairs by code with their counts: keys in README");
  verb->callback([args] { run(*args); });
}

} // namespace sdflow::cli
