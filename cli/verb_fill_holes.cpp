//! `sdflow fill-holes MESH -o OUT [--max-hole-length L] [--json]`: Liepa hole filling of the
//! boundary loops shorter than L; loops that are not simple (figure eight) are reported and left open.

#include "common_options.h"
#include "json_report.h"
#include "verbs.h"
#include "work_progress.h"

#include "sdflow/io/io.h"
#include "sdflow/reconstruct/holes.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <iostream>

#include <map>
#include <memory>
#include <string>

namespace sdflow::cli {
namespace {

struct FillHolesArguments {
  std::string input;
  std::string output;
  HoleFillingOptions options;
  Encoding encoding = Encoding::binary;
  bool json = false;
};

//! The stable JSON name of an outcome.
const char* outcome_code(LoopOutcome outcome)
{
  switch (outcome) {
  case LoopOutcome::filled: return "filled";
  case LoopOutcome::too_long: return "too-long";
  case LoopOutcome::not_simple: return "not-simple";
  case LoopOutcome::untriangulable: return "untriangulable";
  }
  return "?";
}

const char* outcome_name(LoopOutcome outcome)
{
  switch (outcome) {
  case LoopOutcome::filled: return "filled";
  case LoopOutcome::too_long: return "left open: longer than --max-hole-length";
  case LoopOutcome::not_simple: return "left open: not a simple loop (figure eight)";
  case LoopOutcome::untriangulable: return "left open: every triangulation would duplicate an edge";
  }
  return "?";
}

void run(const FillHolesArguments& args)
{
  WorkProgress progress("fill-holes");
  progress.stage("reading " + args.input);
  const BuiltMesh built = read_mesh(args.input);
  progress.stage("filling the boundary loops");
  const FilledHoles result = fill_holes(built.mesh, args.options);
  progress.stage("writing " + args.output);
  write_mesh(result.mesh, args.output, {.encoding = args.encoding, .vertex_fields = surface_fields(result.mesh)});
  progress.finish();
  int filled = 0;
  for (const HoleReport& loop : result.loops)
    filled += loop.outcome == LoopOutcome::filled;
  if (args.json) {
    toml::array loops;
    for (const HoleReport& loop : result.loops)
      loops.push_back(toml::table{{"edges", static_cast<int64_t>(loop.vertices.size())},
                                  {"length", loop.length},
                                  {"vertex", static_cast<int64_t>(loop.vertices.front())},
                                  {"outcome", outcome_code(loop.outcome)},
                                  {"added_vertices", static_cast<int64_t>(loop.added_vertices)},
                                  {"added_faces", static_cast<int64_t>(loop.added_faces)}});
    print_json(toml::table{{"input", args.input},
                           {"output", args.output},
                           {"loops", std::move(loops)},
                           {"filled", filled},
                           {"open", static_cast<int64_t>(result.loops.size()) - filled},
                           {"vertices", static_cast<int64_t>(result.mesh.n_vertices())},
                           {"faces", static_cast<int64_t>(result.mesh.n_faces())}});
    return;
  }
  std::cout << fmt::format("{}: {} of {} boundary loop(s) filled\n", args.input, filled, result.loops.size());
  for (const HoleReport& loop : result.loops) {
    std::cout << fmt::format("  loop of {} edges (length {:.6g}) through vertex {}: {}", loop.vertices.size(),
                             loop.length, loop.vertices.front(), outcome_name(loop.outcome));
    if (loop.outcome == LoopOutcome::filled)
      std::cout << fmt::format(", {} vertices and {} triangles added", loop.added_vertices, loop.added_faces);
    std::cout << '\n';
  }
  std::cout << fmt::format("wrote {} ({} vertices, {} faces)\n", args.output, result.mesh.n_vertices(),
                           result.mesh.n_faces());
}

} // namespace

void add_fill_holes_verb(CLI::App& app)
{
  auto args = std::make_shared<FillHolesArguments>();
  CLI::App* verb = app.add_subcommand(
      "fill-holes", "Fill boundary loops by minimum-weight triangulation, refinement and fairing (Liepa 2003)");
  verb->add_option("mesh", args->input, fmt::format("Mesh file ({})", mesh_formats))->required();
  add_output_option(*verb, args->output, "Output mesh")->required();
  verb->add_option("--max-hole-length,--max-loop-length", args->options.max_loop_length,
                   "Leave open the loops longer than this (default: fill every loop; --max-loop-length: its older "
                   "name)")
      ->check(CLI::NonNegativeNumber);
  add_choice_option(*verb, "--stages", args->options.stages,
                    std::map<std::string, HoleFillingStages>{{"triangulate", HoleFillingStages::triangulate},
                                                             {"refine", HoleFillingStages::refine},
                                                             {"fair", HoleFillingStages::refine_and_fair}},
                    "How far to go: triangulate, refine, or fair (refine and fair)")
      ->default_str("fair");
  add_choice_option(*verb, "--weights", args->options.weights,
                    std::map<std::string, FairingWeights>{{"cotangent", FairingWeights::cotangent},
                                                          {"uniform", FairingWeights::uniform}},
                    "Fairing Laplacian")
      ->default_str("cotangent");
  add_encoding_flags(*verb, args->encoding);
  add_json_flag(*verb, args->json);
  verb->callback([args] { run(*args); });
}

} // namespace sdflow::cli
