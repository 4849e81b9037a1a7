//! `sdflow shape NAME [--param value ...] [--edge-length h | --vertices N] -o OUT`: the paper's
//! initial surfaces (or a formula with --expr) meshed to quality; `sdflow shape --list`.

#include "verbs.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/io/io.h"
#include "sdflow/limits.h"
#include "sdflow/shapes/catalogue.h"
#include "sdflow/shapes/expression.h"
#include "sdflow/shapes/mesher.h"

#include <fmt/format.h>

#include <iostream>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace sdflow::cli {
namespace {

struct ShapeArguments {
  std::string name;
  bool list = false;
  std::string expression;
  std::vector<double> box;
  double feature_size = 0;
  double edge_length = 0;
  int vertices = 0;
  int iterations = MesherOptions{}.iterations;
  double edges_per_radius = 0;
  double grid_cell = 0;
  bool force = false;
  std::string output;
  std::map<std::string, double> values;      //!< every catalogue parameter, by name
  std::map<std::string, CLI::Option*> given; //!< to tell which were given
};

void print_catalogue()
{
  for (const auto& shape : shape_catalogue()) {
    std::cout << fmt::format("{}: {}\n", shape.name, shape.summary);
    for (const auto& p : shape.parameters)
      std::cout << fmt::format("  --{:<20} {:<12.10g} {}\n", p.name, p.default_value, p.description);
  }
  std::cout << "expression: any level set f(x, y, z) = 0 (muparser syntax), negative inside\n"
               "  --expr \"...\" --box xmin,ymin,zmin,xmax,ymax,zmax [--feature-size s]\n";
}

ImplicitSurface chosen_surface(const ShapeArguments& args)
{
  std::vector<std::string> given;
  for (const auto& [name, option] : args.given)
    if (option->count())
      given.push_back(name);
  if (!args.expression.empty()) {
    if (!args.name.empty())
      throw InvalidParameter(fmt::format("give a shape name ('{}') or --expr, not both", args.name));
    if (!given.empty())
      throw InvalidParameter(fmt::format("--{} is a catalogue shape's parameter; an --expr takes none", given[0]));
    if (args.box.size() != 6)
      throw InvalidParameter("--expr needs --box xmin,ymin,zmin,xmax,ymax,zmax");
    return expression_surface({args.expression,
                                       {Eigen::Vector3d(args.box[0], args.box[1], args.box[2]),
                                        Eigen::Vector3d(args.box[3], args.box[4], args.box[5])},
                                       args.feature_size});
  }
  if (args.name.empty())
    throw InvalidParameter("give a shape name (see sdflow shape --list) or --expr");
  if (!args.box.empty() || args.feature_size != 0)
    throw InvalidParameter("--box and --feature-size belong to --expr; catalogue shapes have their own");
  std::map<std::string, double> parameters;
  for (const auto& name : given)
    parameters[name] = args.values.at(name);
  return make_shape(args.name, parameters);
}

void run(const ShapeArguments& args)
{
  if (args.list) {
    print_catalogue();
    return;
  }
  if (args.output.empty())
    throw InvalidParameter("no output file: give -o OUT (.off, .obj, .ply or .stl)");
  format_from_extension(args.output); // refuse an unknown format before meshing
  const SizeLimits limits{.force = args.force};
  check_count(args.iterations, limits.max_iterations, "--iterations", limits);
  const ImplicitSurface surface = chosen_surface(args);
  if (args.vertices > 0)
    check_surface_size(args.vertices, fmt::format("shape --vertices {}", args.vertices), limits, false);
  else if (args.edge_length > 0)
    check_surface_size(estimated_vertices_in_box(surface.box, args.edge_length),
                       fmt::format("shape --edge-length {}", args.edge_length), limits, false);
  const MesherResult result = mesh_implicit_surface(
      surface, {.edge_length = args.edge_length, .vertices = args.vertices, .iterations = args.iterations,
                .edges_per_radius = args.edges_per_radius, .grid_cell = args.grid_cell});
  write_mesh(result.mesh, args.output, {.encoding = Encoding::binary, .vertex_fields = surface_fields(result.mesh)});

  const auto& a = result.min_angles;
  std::cout << fmt::format("{}: {} vertices, {} faces, edge length {:.6g} (marching grid {:.4g}: {} vertices)\n",
                           surface.name, result.mesh.n_vertices(), result.mesh.n_faces(), result.edge_length,
                           result.grid_cell, result.initial_vertices);
  for (const auto& c : component_topology(result.mesh))
    std::cout << fmt::format("  component: {} faces, genus {}, {} boundary loop(s)\n", c.faces, c.genus, c.boundary_loops);
  std::cout << fmt::format("  triangle minimum angle: min {:.2f}°, 1% {:.2f}°, 5% {:.2f}°, 25% {:.2f}°, median {:.2f}°\n",
                           a.min, a.p01, a.p05, a.p25, a.median);
  std::cout << "  per 10° (0-10 ... 50-60):";
  for (long n : a.histogram)
    std::cout << ' ' << n;
  std::cout << fmt::format("\n  largest |f|/|grad f| at a vertex: {:.2e} of the box diagonal\n", result.max_level_set_distance);
  std::cout << fmt::format("  wrote {}\n", args.output);
}

} // namespace

void add_shape_verb(CLI::App& app)
{
  auto args = std::make_shared<ShapeArguments>();
  CLI::App* verb = app.add_subcommand("shape", "Mesh one of the paper's initial surfaces, or a formula, to quality");
  verb->add_option("name", args->name, "Catalogue shape (see --list)");
  verb->add_flag("--list", args->list, "List the shapes and their parameters");
  verb->add_option("--expr", args->expression, "Level set f(x, y, z) = 0 to mesh (muparser syntax), negative inside");
  verb->add_option("--box", args->box, "Box for --expr: xmin,ymin,zmin,xmax,ymax,zmax")->delimiter(',')->expected(6);
  verb->add_option("--feature-size", args->feature_size, "For --expr: smallest neck or gap to resolve");
  auto* length = verb->add_option("--edge-length", args->edge_length, "Target edge length");
  auto* count = verb->add_option("--vertices", args->vertices, "Approximate vertex count (within a few percent)");
  length->excludes(count);
  verb->add_option("--iterations", args->iterations, "Remeshing iterations")->capture_default_str();
  verb->add_option("--edges-per-radius", args->edges_per_radius,
                   "Then refine to this many edges per radius of curvature where finer than the edge length, "
                   "down to a quarter of it (default 0: uniform)")
      ->check(CLI::NonNegativeNumber);
  verb->add_option("--grid-cell", args->grid_cell, "Marching grid spacing (default: from the edge length and shape)");
  verb->add_option("-o,--output", args->output, "Output mesh (.off, .obj, .ply, .stl)");
  verb->add_flag("--force", args->force, "Skip the plausibility limits (size of the result, iterations)");
  // Every catalogue parameter once; which ones the chosen shape accepts is checked after parsing.
  std::map<std::string, std::set<std::string>> users;
  for (const auto& shape : shape_catalogue())
    for (const auto& p : shape.parameters)
      users[p.name].insert(shape.name);
  for (const auto& [name, shapes_using] : users) {
    std::string list;
    for (const auto& s : shapes_using)
      list += (list.empty() ? "" : ", ") + s;
    args->values[name] = 0;
    args->given[name] = verb->add_option("--" + name, args->values[name], fmt::format("Parameter of {}", list));
  }
  verb->callback([args] { run(*args); });
}

} // namespace sdflow::cli
