//! `sdflow shape NAME [--param value ...] [--edge-length h | --vertices N] -o OUT`: the paper's
//! initial surfaces (or a formula with --expr) meshed to quality; `sdflow shape --list`.

#include "common_options.h"
#include "json_report.h"
#include "verbs.h"
#include "work_progress.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/io/io.h"
#include "sdflow/limits.h"
#include "sdflow/shapes/catalogue.h"
#include "sdflow/shapes/expression.h"
#include "sdflow/shapes/mesher.h"
#include "sdflow/shapes/packing.h"

#include <fmt/format.h>
#include <toml++/toml.h>

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
  std::string spheres; //!< packing: a CSV of x,y,z,r
  std::vector<double> box;
  double feature_size = 0;
  double edge_length = 0;
  int vertices = 0;
  int iterations = MesherOptions{}.iterations;
  double edges_per_radius = 0;
  double grid_cell = 0;
  bool force = false;
  std::string output;
  Encoding encoding = Encoding::binary;
  bool json = false;
  std::map<std::string, double> values;      //!< every catalogue parameter, by name
  std::map<std::string, CLI::Option*> given; //!< to tell which were given
};

void print_catalogue(bool json)
{
  if (json) {
    toml::array shapes;
    for (const auto& shape : shape_catalogue()) {
      toml::array parameters;
      for (const auto& p : shape.parameters)
        parameters.push_back(
            toml::table{{"name", p.name}, {"default", p.default_value}, {"description", p.description}});
      shapes.push_back(
          toml::table{{"name", shape.name}, {"summary", shape.summary}, {"parameters", std::move(parameters)}});
    }
    print_json(toml::table{{"shapes", std::move(shapes)}});
    return;
  }
  for (const auto& shape : shape_catalogue()) {
    std::cout << fmt::format("{}: {}\n", shape.name, shape.summary);
    for (const auto& p : shape.parameters)
      std::cout << fmt::format("  --{:<20} {:<12.10g} {}\n", p.name, p.default_value, p.description);
  }
  std::cout << "expression: any level set f(x, y, z) = 0 (muparser syntax), negative inside\n"
               "  --expr \"...\" --box xmin,ymin,zmin,xmax,ymax,zmax [--feature-size s]\n"
               "packing from a file: sdflow shape packing --spheres FILE.csv (x,y,z,r a line) [--blend k]\n";
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
  if (!args.spheres.empty()) {
    if (args.name != "packing")
      throw InvalidParameter(fmt::format("--spheres belongs to the packing shape, not '{}'", args.name));
    for (const auto& name : given)
      if (name != "blend")
        throw InvalidParameter(fmt::format("--{} makes a packing; --spheres reads one (only --blend applies)", name));
    return packing_surface(read_packing_csv(args.spheres), {.blend = parameters.contains("blend") ? parameters["blend"] : PackingSurfaceOptions{}.blend});
  }
  return make_shape(args.name, parameters);
}

void run(const ShapeArguments& args)
{
  if (args.list) {
    print_catalogue(args.json);
    return;
  }
  if (args.output.empty())
    throw InvalidParameter("no output file: give -o OUT (.off, .obj, .ply or .stl)");
  format_from_extension(args.output); // refuse an unknown format before meshing
  const SizeLimits limits{.force = args.force};
  check_count(args.iterations, limits.max_iterations, "--remesh-iterations", limits);
  const ImplicitSurface surface = chosen_surface(args);
  if (args.vertices > 0)
    check_surface_size(args.vertices, fmt::format("shape --vertices {}", args.vertices), limits, false);
  else if (args.edge_length > 0)
    check_surface_size(estimated_vertices_in_box(surface.box, args.edge_length),
                       fmt::format("shape --edge-length {}", args.edge_length), limits, false);
  WorkProgress progress("shape");
  progress.stage(args.vertices > 0 ? fmt::format("meshing '{}' to about {} vertices", surface.name, args.vertices)
                                   : fmt::format("meshing '{}'", surface.name));
  const MesherResult result = mesh_implicit_surface(
      surface, {.edge_length = args.edge_length, .vertices = args.vertices, .iterations = args.iterations,
                .edges_per_radius = args.edges_per_radius, .grid_cell = args.grid_cell});
  progress.stage("writing " + args.output);
  write_mesh(result.mesh, args.output, {.encoding = args.encoding, .vertex_fields = surface_fields(result.mesh)});
  progress.finish();

  const auto& a = result.min_angles;
  if (args.json) {
    toml::array components, histogram;
    for (const auto& c : component_topology(result.mesh))
      components.push_back(toml::table{
          {"faces", static_cast<int64_t>(c.faces)}, {"genus", c.genus}, {"boundary_loops", c.boundary_loops}});
    for (long n : a.histogram)
      histogram.push_back(static_cast<int64_t>(n));
    print_json(toml::table{{"shape", surface.name},
                           {"output", args.output},
                           {"vertices", static_cast<int64_t>(result.mesh.n_vertices())},
                           {"faces", static_cast<int64_t>(result.mesh.n_faces())},
                           {"edge_length", result.edge_length},
                           {"grid_cell", result.grid_cell},
                           {"initial_vertices", static_cast<int64_t>(result.initial_vertices)},
                           {"components", std::move(components)},
                           {"min_angle_deg", toml::table{{"min", a.min}, {"p01", a.p01}, {"p05", a.p05},
                                                         {"p25", a.p25}, {"median", a.median}}},
                           {"min_angle_histogram", std::move(histogram)},
                           {"max_level_set_distance", result.max_level_set_distance}});
    return;
  }
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
  verb->add_option("--spheres", args->spheres, "For packing: a CSV file of spheres, one x,y,z,r a line");
  auto* length = verb->add_option("--edge-length", args->edge_length, "Target edge length");
  auto* count = verb->add_option("--vertices", args->vertices, "Approximate vertex count (within a few percent)");
  length->excludes(count);
  verb->add_option("--remesh-iterations,--iterations", args->iterations,
                   "Remeshing iterations (--iterations: its older name)")
      ->capture_default_str();
  verb->add_option("--edges-per-radius", args->edges_per_radius,
                   "Then refine to this many edges per radius of curvature where finer than the edge length, "
                   "down to a quarter of it (default 0: uniform)")
      ->check(CLI::NonNegativeNumber);
  verb->add_option("--grid-cell", args->grid_cell, "Marching grid spacing (default: from the edge length and shape)");
  add_output_option(*verb, args->output, "Output mesh (.off, .obj, .ply, .stl)");
  add_encoding_flags(*verb, args->encoding);
  add_json_flag(*verb, args->json);
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
