//! `sdflow components MESH [--min-faces N] [--keep-largest N] [--split] -o OUT`: keep the
//! connected components with at least N triangles and/or the N largest (retri/components.h), in
//! one file, or with --split one file per component, largest first: OUT's stem + _0, _1, ...

#include "verbs.h"

#include "sdflow/io/io.h"
#include "sdflow/io/repair.h"
#include "sdflow/retri/components.h"

#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <string>

namespace sdflow::cli {
namespace {

struct ComponentsArguments {
  std::string mesh;
  std::string output;
  ComponentOptions options;
  bool split = false;
};

std::filesystem::path numbered(const std::filesystem::path& output, std::size_t i)
{
  std::filesystem::path p = output;
  p.replace_filename(fmt::format("{}_{}{}", output.stem().string(), i, output.extension().string()));
  return p;
}

void run(const ComponentsArguments& args)
{
  const Mesh mesh = read_mesh_or_repair(args.mesh).mesh;
  const ComponentSelection selection = keep_components(mesh, args.options);
  std::cout << fmt::format("{}: {} component(s); keeping {}, dropping {}\n", args.mesh, selection.faces.size(),
                           selection.kept.size(), selection.dropped.size());
  for (int c : selection.kept)
    std::cout << fmt::format("  kept component {}: {} faces\n", c, selection.faces[c]);
  for (int c : selection.dropped)
    std::cout << fmt::format("  dropped component {}: {} faces\n", c, selection.faces[c]);
  if (!args.split) {
    write_mesh(selection.mesh, args.output);
    std::cout << fmt::format("wrote {} ({} faces)\n", args.output, selection.mesh.n_faces());
    return;
  }
  const std::vector<Mesh> parts = split_components(mesh, args.options);
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const auto file = numbered(args.output, i);
    write_mesh(parts[i], file);
    std::cout << fmt::format("wrote {} ({} faces)\n", file.string(), parts[i].n_faces());
  }
}

} // namespace

void add_components_verb(CLI::App& app)
{
  auto args = std::make_shared<ComponentsArguments>();
  CLI::App* verb = app.add_subcommand("components", "Keep the large connected components, or split into one file each");
  verb->add_option("mesh", args->mesh, "Mesh file (OFF, OBJ, PLY, STL)")->required();
  verb->add_option("-o,--output", args->output, "Output mesh (with --split: OUT_0.ext, OUT_1.ext, ... largest first)")
    ->required();
  verb->add_option("--min-faces", args->options.min_faces, "Keep components with at least N triangles")
    ->check(CLI::PositiveNumber);
  verb->add_option("--keep-largest", args->options.keep_largest, "Then keep only the N largest (0: all)")
    ->check(CLI::NonNegativeNumber);
  verb->add_flag("--split", args->split, "Write every kept component to its own file");
  verb->callback([args] { run(*args); });
}

} // namespace sdflow::cli
