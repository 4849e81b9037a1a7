//! `sdflow components MESH [--min-component-faces N] [--keep-largest N] [--split] -o OUT [--json]`:
//! keep the connected components with at least N triangles and/or the N largest
//! (retri/components.h), in one file, or with --split one file per component, largest first:
//! OUT's stem + _0, _1, ...

#include "common_options.h"
#include "json_report.h"
#include "verbs.h"
#include "work_progress.h"

#include "sdflow/io/io.h"
#include "sdflow/io/repair.h"
#include "sdflow/retri/components.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

namespace sdflow::cli {
namespace {

struct ComponentsArguments {
  std::string mesh;
  std::string output;
  ComponentOptions options;
  Encoding encoding = Encoding::binary;
  bool split = false;
  bool json = false;
};

std::filesystem::path numbered(const std::filesystem::path& output, std::size_t i)
{
  std::filesystem::path p = output;
  p.replace_filename(fmt::format("{}_{}{}", output.stem().string(), i, output.extension().string()));
  return p;
}

void run(const ComponentsArguments& args)
{
  WorkProgress progress("components");
  progress.stage("reading " + args.mesh);
  const Mesh mesh = read_mesh_or_repair(args.mesh).mesh;
  progress.stage(fmt::format("sorting {} faces into components", mesh.n_faces()));
  const ComponentSelection selection = keep_components(mesh, args.options);
  std::vector<std::pair<std::string, const Mesh*>> written;
  std::vector<Mesh> parts;
  if (args.split) {
    progress.stage(fmt::format("splitting {} components", selection.kept.size()));
    parts = split_components(mesh, args.options);
    for (std::size_t i = 0; i < parts.size(); ++i)
      written.emplace_back(numbered(args.output, i).string(), &parts[i]);
  } else {
    written.emplace_back(args.output, &selection.mesh);
  }
  for (const auto& [file, part] : written) {
    progress.stage("writing " + file);
    write_mesh(*part, file, {.encoding = args.encoding, .vertex_fields = surface_fields(*part)});
  }
  progress.finish();

  if (args.json) {
    toml::array components, outputs;
    for (std::size_t c = 0; c < selection.faces.size(); ++c) {
      const bool kept = std::find(selection.kept.begin(), selection.kept.end(), static_cast<int>(c)) !=
                        selection.kept.end();
      components.push_back(toml::table{{"faces", selection.faces[c]}, {"kept", kept}});
    }
    for (const auto& [file, part] : written)
      outputs.push_back(toml::table{{"file", file},
                                    {"vertices", static_cast<int64_t>(part->n_vertices())},
                                    {"faces", static_cast<int64_t>(part->n_faces())}});
    print_json(toml::table{{"input", args.mesh},
                           {"component_count", static_cast<int64_t>(selection.faces.size())},
                           {"kept", static_cast<int64_t>(selection.kept.size())},
                           {"dropped", static_cast<int64_t>(selection.dropped.size())},
                           {"components", std::move(components)},
                           {"outputs", std::move(outputs)}});
    return;
  }
  std::cout << fmt::format("{}: {} component(s); keeping {}, dropping {}\n", args.mesh, selection.faces.size(),
                           selection.kept.size(), selection.dropped.size());
  for (int c : selection.kept)
    std::cout << fmt::format("  kept component {}: {} faces\n", c, selection.faces[c]);
  for (int c : selection.dropped)
    std::cout << fmt::format("  dropped component {}: {} faces\n", c, selection.faces[c]);
  for (const auto& [file, part] : written)
    std::cout << fmt::format("wrote {} ({} faces)\n", file, part->n_faces());
}

} // namespace

void add_components_verb(CLI::App& app)
{
  auto args = std::make_shared<ComponentsArguments>();
  CLI::App* verb = app.add_subcommand("components", "Keep the large connected components, or split into one file each");
  verb->add_option("mesh", args->mesh, fmt::format("Mesh file ({})", mesh_formats))->required();
  add_output_option(*verb, args->output, "Output mesh (with --split: OUT_0.ext, OUT_1.ext, ... largest first)")
      ->required();
  verb->add_option("--min-component-faces,--min-faces", args->options.min_faces,
                   "Keep components with at least N triangles (--min-faces: its older name)")
      ->check(CLI::PositiveNumber);
  verb->add_option("--keep-largest", args->options.keep_largest, "Then keep only the N largest (0: all)")
    ->check(CLI::NonNegativeNumber);
  verb->add_flag("--split", args->split, "Write every kept component to its own file");
  add_encoding_flags(*verb, args->encoding);
  add_json_flag(*verb, args->json);
  verb->callback([args] { run(*args); });
}

} // namespace sdflow::cli
