//! `sdflow remesh IN -o OUT --edge-length h [--remesh-iterations k] [--keep-boundary] [--json]`: isotropic
//! remeshing (Botsch & Kobbelt 2004) onto the input surface.

#include "common_options.h"
#include "json_report.h"
#include "verbs.h"
#include "work_progress.h"

#include "sdflow/check/span.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/io/io.h"
#include "sdflow/limits.h"
#include "sdflow/remesh/remesh.h"

#include <fmt/format.h>
#include <toml++/toml.h>

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
  Encoding encoding = Encoding::binary;
  bool json = false;
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
  check_count(args.iterations, limits.max_iterations, "--remesh-iterations", limits);
  WorkProgress progress("remesh");
  progress.stage("reading " + args.input);
  const BuiltMesh input = read_mesh(args.input);
  check_span(input.mesh, args.input); // a far vertex would also make the size estimate meaningless
  check_remeshed_size(input.mesh, args.edge_length, fmt::format("remesh --edge-length {}", args.edge_length), limits);
  progress.stage(fmt::format("{} iterations to edge length {:.6g}", args.iterations, args.edge_length));
  // Projection onto the input surface (its BVH) and its boundary polylines: the defaults.
  const RemeshResult result = isotropic_remesh(
      input.mesh, {.edge_length = args.edge_length,
                   .iterations = args.iterations,
                   .boundary = args.keep_boundary ? BoundaryMode::keep : BoundaryMode::remesh,
                   .settle_kept_boundary = args.keep_boundary});
  progress.stage("writing " + args.output);
  write_mesh(result.mesh, args.output, {.encoding = args.encoding, .vertex_fields = surface_fields(result.mesh)});
  progress.finish();
  int in_band = 0;
  for (auto e : result.mesh.edges()) {
    const double r = result.mesh.calc_edge_length(e) / args.edge_length;
    in_band += r >= 0.8 && r <= 4.0 / 3.0;
  }
  const auto& s = result.statistics;
  const double in_band_fraction = result.mesh.n_edges() > 0 ? static_cast<double>(in_band) / result.mesh.n_edges() : 0.0;
  if (args.json) {
    print_json(toml::table{{"input", args.input},
                           {"output", args.output},
                           {"input_vertices", static_cast<int64_t>(input.mesh.n_vertices())},
                           {"input_faces", static_cast<int64_t>(input.mesh.n_faces())},
                           {"vertices", static_cast<int64_t>(result.mesh.n_vertices())},
                           {"faces", static_cast<int64_t>(result.mesh.n_faces())},
                           {"edge_length", args.edge_length},
                           {"edges_in_band_fraction", in_band_fraction},
                           {"splits", static_cast<int64_t>(s.splits)},
                           {"collapses", static_cast<int64_t>(s.collapses)},
                           {"flips", static_cast<int64_t>(s.flips)}});
    return;
  }
  std::cout << fmt::format("{}: {} vertices, {} faces ({}) -> {} vertices, {} faces ({})\n", args.input,
                           input.mesh.n_vertices(), input.mesh.n_faces(), topology_text(input.mesh),
                           result.mesh.n_vertices(), result.mesh.n_faces(), topology_text(result.mesh));
  std::cout << fmt::format("  {:.1f}% of edges within [4/5, 4/3] x {:.6g}; {} splits, {} collapses, {} flips\n",
                           100.0 * in_band_fraction, args.edge_length, s.splits, s.collapses, s.flips);
  std::cout << fmt::format("  wrote {}\n", args.output);
}

} // namespace

void add_remesh_verb(CLI::App& app)
{
  auto args = std::make_shared<RemeshArguments>();
  CLI::App* verb = app.add_subcommand("remesh", "Isotropic remeshing to a target edge length (Botsch & Kobbelt 2004)");
  verb->add_option("input", args->input, fmt::format("Input mesh ({})", mesh_formats))->required();
  add_output_option(*verb, args->output, "Output mesh")->required();
  verb->add_option("--edge-length", args->edge_length, "Target edge length")->required()->check(CLI::PositiveNumber);
  verb->add_option("--remesh-iterations,--iterations", args->iterations,
                   "Remeshing iterations (--iterations: its older name)")->capture_default_str()->check(CLI::NonNegativeNumber);
  verb->add_flag("--force", args->force, "Skip the plausibility limits (size of the result, iterations)");
  verb->add_flag("--keep-boundary", args->keep_boundary,
                 "Leave boundary vertices and edges exactly as they are (the vertices beside them then settle, "
                 "which evens out the edges to the boundary)");
  add_encoding_flags(*verb, args->encoding);
  add_json_flag(*verb, args->json);
  verb->callback([args] { run(*args); });
}

} // namespace sdflow::cli
