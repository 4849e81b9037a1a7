//! `sdflow remesh IN -o OUT --edge-length h [--iterations k] [--keep-boundary]`: isotropic
//! remeshing (Botsch & Kobbelt 2004) onto the input surface.

#include "verbs.h"

#include "sdflow/geometry/topology.h"
#include "sdflow/io/io.h"
#include "sdflow/limits.h"
#include "sdflow/remesh/remesh.h"

#include <fmt/format.h>

#include <iostream>
#include <string>

namespace sdflow::cli {
namespace {

struct RemeshArguments {
  std::string input;
  std::string output;
  double edge_length = 0;
  int iterations = RemeshOptions{}.iterations;
  bool keep_boundary = false;
  bool force = false;
};

std::string topology_text(const Mesh& mesh)
{
  std::string text;
  for (const auto& c : component_topology(mesh))
    text += fmt::format("{}genus {} / {} boundary loop(s)", text.empty() ? "" : ", ", c.genus, c.boundary_loops);
  return text;
}

void run(const RemeshArguments& args)
{
  format_from_extension(args.output); // refuse an unknown format before the work
  const SizeLimits limits{.force = args.force};
  check_count(args.iterations, limits.max_iterations, "--iterations", limits);
  const BuiltMesh input = read_mesh(args.input);
  check_remeshed_size(input.mesh, args.edge_length, fmt::format("remesh --edge-length {}", args.edge_length), limits);
  // Projection onto the input surface (its BVH) and its boundary polylines: the defaults.
  const RemeshResult result = isotropic_remesh(
      input.mesh, {.edge_length = args.edge_length,
                   .iterations = args.iterations,
                   .boundary = args.keep_boundary ? BoundaryMode::keep : BoundaryMode::remesh});
  write_mesh(result.mesh, args.output, {.encoding = Encoding::binary});
  int in_band = 0;
  for (auto e : result.mesh.edges()) {
    const double r = result.mesh.calc_edge_length(e) / args.edge_length;
    in_band += r >= 0.8 && r <= 4.0 / 3.0;
  }
  const auto& s = result.statistics;
  std::cout << fmt::format("{}: {} vertices, {} faces ({}) -> {} vertices, {} faces ({})\n", args.input,
                           input.mesh.n_vertices(), input.mesh.n_faces(), topology_text(input.mesh),
                           result.mesh.n_vertices(), result.mesh.n_faces(), topology_text(result.mesh));
  std::cout << fmt::format("  {:.1f}% of edges within [4/5, 4/3] x {:.6g}; {} splits, {} collapses, {} flips\n",
                           100.0 * in_band / result.mesh.n_edges(), args.edge_length, s.splits, s.collapses, s.flips);
  std::cout << fmt::format("  wrote {}\n", args.output);
}

} // namespace

void add_remesh_verb(CLI::App& app)
{
  auto args = std::make_shared<RemeshArguments>();
  CLI::App* verb = app.add_subcommand("remesh", "Isotropic remeshing to a target edge length (Botsch & Kobbelt 2004)");
  verb->add_option("input", args->input, "Input mesh (OFF, OBJ, PLY, STL)")->required();
  verb->add_option("-o,--output", args->output, "Output mesh")->required();
  verb->add_option("--edge-length", args->edge_length, "Target edge length")->required()->check(CLI::PositiveNumber);
  verb->add_option("--iterations", args->iterations, "Remeshing iterations")->capture_default_str()->check(CLI::NonNegativeNumber);
  verb->add_flag("--force", args->force, "Skip the plausibility limits (size of the result, iterations)");
  verb->add_flag("--keep-boundary", args->keep_boundary, "Leave boundary vertices and edges exactly as they are");
  verb->callback([args] { run(*args); });
}

} // namespace sdflow::cli
