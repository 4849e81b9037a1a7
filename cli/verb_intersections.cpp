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
  //! One surface whose search merged bit-identical points at a pinch: the pairs of its repaired
  //! copy, which splits such points (io/repair.h, non-manifold-vertex), and how many it split.
  std::optional<std::size_t> repaired_pairs;
  std::size_t split_points = 0;
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
    const PolygonSoup polygons = read_polygon_soup(args.mesh);
    const TriangleSoup soup = triangle_soup(polygons, args.mesh);
    faces = static_cast<std::size_t>(soup.triangles.rows());
    progress.stage(fmt::format("testing {} faces against each other", faces));
    pairs = self_intersections(soup.positions, soup.triangles);
    if (soup.merged_vertices > 0) {
      // Faces meeting at a merged point share it as a corner here. A repair keeps such a point
      // where one fan of faces meets (a seam) but splits it where several do (a pinch), and its
      // copy then decides the faces that met only there without the shared corner: the counts
      // can differ, and the repaired copy's is given beside this one (issue 32).
      try {
        const RepairResult repaired = repair_soup(polygons, args.mesh);
        split_points = repaired.count("non-manifold-vertex");
        if (split_points > 0) {
          progress.stage("testing the repaired copy's faces");
          repaired_pairs = self_intersections(repaired.mesh).size();
        }
      } catch (const Error&) {
        // A file no repair fixes has no repaired copy to compare with.
      }
    }
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
    if (repaired_pairs) {
      root.insert("repaired_intersecting_pairs", static_cast<int64_t>(*repaired_pairs));
      root.insert("repair_split_points", static_cast<int64_t>(split_points));
    }
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
  if (repaired_pairs)
    std::cout << fmt::format(
        "its repaired copy (sdflow repair) has {} intersecting pair(s){}: the repair splits {} point(s) where separate "
        "fans of faces meet, which this search takes as one corner (bit-identical points merged), so faces that "
        "met only there are neighbours here and are tested as strangers there\n",
        *repaired_pairs, *repaired_pairs == pairs.size() ? ", the same count" : fmt::format(", not {}", pairs.size()),
        split_points);
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
