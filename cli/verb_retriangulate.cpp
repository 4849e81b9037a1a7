//! `sdflow retriangulate IN -o OUT [--edge-length L] [...] [--json]`: the whole re-triangulation of
//! paper §3.2.1 with Appendix B (retri/pipeline.h), as a run applies it between steps.

#include "common_options.h"
#include "json_report.h"
#include "verbs.h"
#include "work_progress.h"

#include "sdflow/check/span.h"
#include "sdflow/io/io.h"
#include "sdflow/io/repair.h"
#include "sdflow/limits.h"
#include "sdflow/log.h"
#include "sdflow/retri/input_checks.h"
#include "sdflow/retri/pipeline.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <iostream>
#include <memory>
#include <optional>
#include <string>

namespace sdflow::cli {
namespace {

struct RetriangulateArguments {
  std::string input;
  std::string output;
  RetriangulationOptions options;
  Encoding encoding = Encoding::binary;
  bool json = false;
  bool force = false;
};

void report_json(const RetriangulateArguments& args, const BuiltMesh& input, const RetriangulationResult& r)
{
  const auto& s = r.seconds;
  toml::table stages{{"merge", s.merge},         {"remesh", s.remesh},
                     {"intersections", s.intersections}, {"normals", s.normals},
                     {"reconstruction", s.reconstruction}, {"holes", s.holes},
                     {"components", s.components}};
  toml::table root{{"input", args.input},
                   {"output", args.output},
                   {"input_vertices", static_cast<int64_t>(input.mesh.n_vertices())},
                   {"input_faces", static_cast<int64_t>(input.mesh.n_faces())},
                   {"vertices", static_cast<int64_t>(r.mesh.n_vertices())},
                   {"faces", static_cast<int64_t>(r.mesh.n_faces())},
                   {"edge_length", r.edge_length},
                   {"merged_components", r.merged_components},
                   {"splits", static_cast<int64_t>(r.remesh.splits)},
                   {"collapses", static_cast<int64_t>(r.remesh.collapses)},
                   {"flips", static_cast<int64_t>(r.remesh.flips)},
                   {"remeshing_crossings", r.remeshing_crossings},
                   {"remeshing_refinements", r.refinements},
                   {"remeshing_refused", r.remeshing_refused},
                   {"intersecting_pairs", r.intersecting_pairs},
                   {"removed_faces", r.removed_faces},
                   {"rebuilt", r.rebuilt},
                   {"rebuilt_apart", r.rebuilt_apart},
                   {"removed_points", r.removed_points},
                   {"unused_points", r.unused_points},
                   {"filled_holes", r.filled_holes},
                   {"open_holes", r.open_holes},
                   {"components_before", r.components_before},
                   {"components_after", r.components_after},
                   {"dropped_components", r.dropped_components},
                   {"seconds", stages}};
  print_json(std::move(root));
}

//! Stage 1's line of the text report: what the remeshing did, or why it was refused (the wording of
//! retriangulation_summary, retri/pipeline.cpp).
std::string remeshing_line(const RetriangulationResult& r)
{
  if (r.remeshing_refused) {
    std::string why;
    if (r.remeshing_crossings == 0)
      why = "it grew past the bound on its vertices";
    else if (r.refinements == 0)
      why = fmt::format("it made {} face pairs of a surface that did not cross itself cross, and a round finer there "
                        "would have made too many vertices",
                        r.remeshing_crossings);
    else
      why = fmt::format("it made {} face pairs of a surface that did not cross itself cross, and {} round(s) finer "
                        "there did not help",
                        r.remeshing_crossings, r.refinements);
    return fmt::format("remeshing to edge length {:.6g} refused: {}; the surface kept its triangles", r.edge_length,
                       why);
  }
  std::string line = fmt::format("remeshed to edge length {:.6g}: {} splits, {} collapses, {} flips", r.edge_length,
                                 r.remesh.splits, r.remesh.collapses, r.remesh.flips);
  if (r.remeshing_crossings > 0)
    line += fmt::format(", redone {} time(s) finer where it made {} face pairs cross", r.refinements,
                        r.remeshing_crossings);
  return line;
}

void report_text(const RetriangulateArguments& args, const BuiltMesh& input, const RetriangulationResult& r)
{
  std::cout << fmt::format("{}: {} vertices, {} faces, {} component(s) -> {} vertices, {} faces, {} component(s)\n",
                           args.input, input.mesh.n_vertices(), input.mesh.n_faces(), r.components_before,
                           r.mesh.n_vertices(), r.mesh.n_faces(), r.components_after);
  if (r.merged_components > 0)
    std::cout << fmt::format("  0. {} intersecting component(s) joined into others (Appendix B)\n",
                             r.merged_components);
  std::cout << "  1. " << remeshing_line(r) << fmt::format(" ({:.3f} s)\n", r.seconds.remesh);
  std::cout << fmt::format("  2. {} intersecting face pairs, {} faces removed ({:.3f} s)\n", r.intersecting_pairs,
                           r.removed_faces, r.seconds.intersections);
  if (r.rebuilt) {
    std::cout << fmt::format("  3. {} inconsistently oriented points dropped ({:.3f} s)\n", r.removed_points,
                             r.seconds.normals);
    std::cout << fmt::format("  4. surface rebuilt from the points{}, {} unused ({:.3f} s)\n",
                             r.rebuilt_apart ? ", each piece apart (together they bridged a cut)" : "",
                             r.unused_points, r.seconds.reconstruction);
    std::cout << fmt::format("  5. {} hole(s) filled ({:.3f} s)\n", r.filled_holes, r.seconds.holes);
  } else {
    std::cout << fmt::format("  3-5. nothing intersects: the {} surface is kept\n",
                             r.remeshing_refused ? "input's" : "remeshed");
  }
  std::cout << fmt::format("  6. {} debris component(s) dropped (small or flat); {} boundary loop(s) remain\n", r.dropped_components,
                           r.open_holes);
  std::cout << fmt::format("  wrote {}\n", args.output);
}

void run(const RetriangulateArguments& args)
{
  format_from_extension(args.output); // refuse an unknown format before the work
  const SizeLimits limits{.force = args.force};
  check_count(args.options.remesh_iterations, limits.max_iterations, "--remesh-iterations", limits);
  const BuiltMesh input = read_mesh_or_repair(args.input);
  check_span(input.mesh, args.input); // a far vertex would also make the size estimate meaningless
  RetriangulationOptions options = args.options;
  if (options.edge_length == 0)
    if (const std::optional<double> ell = coarse_component_edge_length(input.mesh, options)) {
      options.edge_length = *ell;
      logger().info("{}: a component is too coarse to re-triangulate at the mean edge length: using "
                    "--edge-length {:.3g}, which gives the smallest one enough vertices",
                    args.input, *ell);
    }
  check_remeshed_size(input.mesh, options.edge_length,
                      fmt::format("retriangulate --edge-length {}", options.edge_length), limits);
  check_retriangulation_input(input.mesh, options, args.input);
  WorkProgress progress("retriangulate");
  progress.stage(fmt::format("re-triangulating {} faces", input.mesh.n_faces()));
  const RetriangulationResult result = retriangulate(input.mesh, options);
  progress.stage("writing " + args.output);
  write_mesh(result.mesh, args.output, {.encoding = args.encoding, .vertex_fields = surface_fields(result.mesh)});
  progress.finish();
  if (args.json)
    report_json(args, input, result);
  else
    report_text(args, input, result);
}

} // namespace

void add_retriangulate_verb(CLI::App& app)
{
  auto args = std::make_shared<RetriangulateArguments>();
  RetriangulationOptions& o = args->options;
  CLI::App* verb = app.add_subcommand(
      "retriangulate", "The re-triangulation pipeline of paper §3.2.1: remesh, remove self-intersections, jet + MST "
                       "normals, advancing-front reconstruction, hole filling, components");
  verb->add_option("input", args->input, fmt::format("Input mesh ({})", mesh_formats))->required();
  add_output_option(*verb, args->output, "Output mesh")->required();
  verb->add_option("--edge-length", o.edge_length, "Target edge length (default: the input's mean)")
      ->check(CLI::PositiveNumber);
  verb->add_option("--remesh-iterations,--iterations", o.remesh_iterations,
                   "Remeshing iterations (0: no remeshing; --iterations: its older name)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  verb->add_option("--edges-per-radius", o.edges_per_radius,
                   "Edges per radius of curvature where that is finer than the edge length (0: uniform)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  verb->add_flag("--always-rebuild", o.always_rebuild,
                 "Rebuild from the points even when nothing intersects (stages 3-5 always)");
  verb->add_flag("--keep-boundary", o.keep_boundary,
                 "Keep the boundary loops vertex for vertex, as a run with a fixed boundary does: stage 1 keeps "
                 "them and the rebuild keeps a band of faces along them");
  verb->add_option("--neighbours", o.normals.neighbours, "k, the nearest neighbours of the jet normals (6 to 1000)")
      ->capture_default_str()
      ->check(CLI::Range(6, 1000));
  verb->add_flag("--fill-holes,!--no-fill-holes", o.fill_holes,
                 "Fill the holes the rebuild leaves (the default), or leave them open");
  verb->add_option("--max-hole-length", o.max_hole_length,
                   "Fill only holes shorter than this (default: every hole of a closed surface, else those shorter "
                   "than its shortest boundary loop)")
      ->check(CLI::PositiveNumber);
  verb->add_option("--min-component-faces", o.min_component_faces, "Drop components with fewer triangles")
      ->capture_default_str()
      ->check(CLI::Range(1, 1 << 30));
  verb->add_option("--min-component-thickness", o.min_component_thickness,
                   "Drop closed components whose volume is below this times ℓ times their area")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  verb->add_flag("--force", args->force, "Skip the plausibility limits (size of the result, iterations)");
  add_encoding_flags(*verb, args->encoding);
  add_json_flag(*verb, args->json, "what each stage did, keys documented in README.md");
  verb->callback([args] { run(*args); });
}

} // namespace sdflow::cli
