//! `sdflow intersections MESH [OTHER] [--json] [-o OUT]`: the intersecting face pairs of a surface
//! (or between two surfaces), decided exactly (spatial/intersect.h); with -o, the surface without
//! them (retri/remove_intersections.h). Exit code 0 whether or not pairs are found. A file that is
//! not a valid mesh is searched as the faces it lists (io/repair.h, triangle_soup), or repaired first
//! for -o and for two surfaces.

#include "common_options.h"
#include "json_report.h"
#include "verbs.h"
#include "work_progress.h"

#include "sdflow/errors.h"
#include "sdflow/io/io.h"
#include "sdflow/io/repair.h"
#include "sdflow/retri/remove_intersections.h"
#include "sdflow/spatial/intersect.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <iostream>
#include <optional>
#include <string>

namespace sdflow::cli {
namespace {

struct IntersectionsArguments {
  std::string mesh;
  std::string other;
  std::string output;
  Encoding encoding = Encoding::binary;
  bool json = false;
};

toml::array pair_array(const std::vector<FacePair>& pairs)
{
  toml::array out;
  for (const FacePair& p : pairs)
    out.push_back(toml::array{p.first, p.second});
  return out;
}

void run(const IntersectionsArguments& args)
{
  if (!args.other.empty() && !args.output.empty())
    throw InvalidParameter("intersections: -o removes the intersecting faces of one surface; it cannot be used "
                           "with a second surface");
  // The pairs of one surface are those of the faces the file lists, valid mesh or not; the other
  // uses need a surface, repaired when the file is damaged (io/repair.h).
  std::size_t faces = 0;
  std::vector<FacePair> pairs;
  std::optional<RemovalResult> removal;
  WorkProgress progress("intersections");
  progress.stage("reading " + args.mesh);
  if (!args.other.empty()) {
    const Mesh mesh = read_mesh_or_repair(args.mesh).mesh;
    faces = mesh.n_faces();
    progress.stage("reading " + args.other);
    const Mesh other = read_mesh_or_repair(args.other).mesh;
    progress.stage(fmt::format("testing {} against {} faces", faces, other.n_faces()));
    pairs = surface_intersections(mesh, other);
  } else if (!args.output.empty()) {
    const Mesh mesh = read_mesh_or_repair(args.mesh).mesh;
    faces = mesh.n_faces();
    progress.stage(fmt::format("finding and removing the intersecting faces among {}", faces));
    removal = remove_self_intersections(mesh);
    pairs = removal->intersecting_pairs;
    progress.stage("writing " + args.output);
    write_mesh(removal->mesh, args.output,
               {.encoding = args.encoding, .vertex_fields = surface_fields(removal->mesh)});
  } else {
    const TriangleSoup soup = triangle_soup(read_polygon_soup(args.mesh), args.mesh);
    faces = static_cast<std::size_t>(soup.triangles.rows());
    progress.stage(fmt::format("testing {} faces against each other", faces));
    pairs = self_intersections(soup.positions, soup.triangles);
  }
  progress.finish();
  int degenerate = 0;
  for (const FacePair& p : pairs)
    degenerate += args.other.empty() && p.first == p.second;

  if (args.json) {
    toml::table root{{"file", args.mesh},
                     {"faces", static_cast<int64_t>(faces)},
                     {"intersecting_pairs", static_cast<int64_t>(pairs.size())},
                     {"pairs", pair_array(pairs)}};
    if (!args.other.empty())
      root.insert("other", args.other);
    else
      root.insert("degenerate_faces", degenerate);
    if (removal) {
      root.insert("output", args.output);
      root.insert("removed_faces", static_cast<int64_t>(removal->removed_faces.size()));
      root.insert("removed_vertices", static_cast<int64_t>(removal->removed_vertices.size()));
      root.insert("pinched_vertices", static_cast<int64_t>(removal->pinched_vertices.size()));
    }
    print_json(std::move(root));
    return;
  }
  if (args.other.empty())
    std::cout << fmt::format("{}: {} intersecting face pair(s), {} degenerate face(s) among them as (f, f)\n",
                             args.mesh, pairs.size(), degenerate);
  else
    std::cout << fmt::format("{} and {}: {} intersecting face pair(s) (face of the first, face of the second)\n",
                             args.mesh, args.other, pairs.size());
  for (const FacePair& p : pairs)
    std::cout << fmt::format("  {} {}\n", p.first, p.second);
  if (removal)
    std::cout << fmt::format("removed {} face(s) and {} vertex(es); {} pinched vertex(es) remain; wrote {}\n",
                             removal->removed_faces.size(), removal->removed_vertices.size(),
                             removal->pinched_vertices.size(), args.output);
}

} // namespace

void add_intersections_verb(CLI::App& app)
{
  auto args = std::make_shared<IntersectionsArguments>();
  CLI::App* verb = app.add_subcommand(
    "intersections", "List the intersecting face pairs of a surface (exact), or between two surfaces; -o removes them");
  verb->add_option("mesh", args->mesh, fmt::format("Mesh file ({})", mesh_formats))->required();
  verb->add_option("other", args->other, "Second mesh: list the pairs between the two surfaces instead");
  add_output_option(*verb, args->output,
                    "Write the surface without its intersecting faces and the vertices they leave alone");
  add_encoding_flags(*verb, args->encoding);
  add_json_flag(*verb, args->json);
  verb->callback([args] { run(*args); });
}

} // namespace sdflow::cli
