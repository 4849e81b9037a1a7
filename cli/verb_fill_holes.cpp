//! `sdflow fill-holes MESH -o OUT [--max-loop-length L]`: Liepa hole filling of the boundary loops
//! shorter than L; loops that are not simple (figure eight) are reported and left open.

#include "verbs.h"

#include "sdflow/io/io.h"
#include "sdflow/log.h"
#include "sdflow/reconstruct/holes.h"

#include <fmt/format.h>

#include <map>
#include <memory>
#include <string>

namespace sdflow::cli {
namespace {

struct FillHolesArguments {
  std::string input;
  std::string output;
  HoleFillingOptions options;
  bool binary = false;
};

const char* outcome_name(LoopOutcome outcome)
{
  switch (outcome) {
  case LoopOutcome::filled: return "filled";
  case LoopOutcome::too_long: return "left open: longer than --max-loop-length";
  case LoopOutcome::not_simple: return "left open: not a simple loop (figure eight)";
  case LoopOutcome::untriangulable: return "left open: every triangulation would duplicate an edge";
  }
  return "?";
}

} // namespace

void add_fill_holes_verb(CLI::App& app)
{
  auto args = std::make_shared<FillHolesArguments>();
  CLI::App* verb = app.add_subcommand(
      "fill-holes", "Fill boundary loops by minimum-weight triangulation, refinement and fairing (Liepa 2003)");
  verb->add_option("mesh", args->input, "Mesh file (OFF, OBJ, PLY, STL)")->required();
  verb->add_option("-o,--output", args->output, "Output mesh")->required();
  verb->add_option("--max-loop-length", args->options.max_loop_length,
                   "Leave open the loops longer than this (default: fill every loop)")
      ->check(CLI::NonNegativeNumber);
  verb->add_option("--stages", args->options.stages, "How far to go: triangulate, refine, or fair (refine and fair)")
      ->transform(CLI::CheckedTransformer(
          std::map<std::string, HoleFillingStages>{{"triangulate", HoleFillingStages::triangulate},
                                                   {"refine", HoleFillingStages::refine},
                                                   {"fair", HoleFillingStages::refine_and_fair}},
          CLI::ignore_case))
      ->default_str("fair");
  verb->add_option("--weights", args->options.weights, "Fairing Laplacian: cotangent or uniform")
      ->transform(CLI::CheckedTransformer(std::map<std::string, FairingWeights>{{"cotangent", FairingWeights::cotangent},
                                                                                {"uniform", FairingWeights::uniform}},
                                          CLI::ignore_case))
      ->default_str("cotangent");
  verb->add_flag("--binary", args->binary, "Write binary PLY or STL");
  verb->callback([args] {
    const BuiltMesh built = read_mesh(args->input);
    const FilledHoles result = fill_holes(built.mesh, args->options);
    write_mesh(result.mesh, args->output, {.encoding = args->binary ? Encoding::binary : Encoding::ascii,
                                           .vertex_fields = surface_fields(result.mesh)});
    int filled = 0;
    for (const HoleReport& loop : result.loops) {
      filled += loop.outcome == LoopOutcome::filled;
      const auto message = fmt::format("loop of {} edges (length {:.6g}) through vertex {}: {}", loop.vertices.size(),
                                       loop.length, loop.vertices.front(), outcome_name(loop.outcome));
      if (loop.outcome == LoopOutcome::filled)
        logger().info("{}, {} vertices and {} triangles added", message, loop.added_vertices, loop.added_faces);
      else
        logger().warn("{}", message);
    }
    logger().info("{}: {} of {} boundary loop(s) filled, written to {}", args->input, filled, result.loops.size(),
                  args->output);
  });
}

} // namespace sdflow::cli
