//! `sdflow union A B -o OUT [--json]`: the boundary of the union of two closed surfaces (Appendix B).

#include "common_options.h"
#include "json_report.h"
#include "verbs.h"
#include "work_progress.h"

#include "sdflow/io/io.h"
#include "sdflow/retri/surface_union.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <iostream>
#include <string>

namespace sdflow::cli {
namespace {

struct UnionArguments {
  std::string first, second, output;
  Encoding encoding = Encoding::binary;
  bool json = false;
};

void run(const UnionArguments& args)
{
  WorkProgress progress("union");
  progress.stage("reading " + args.first + " and " + args.second);
  const Mesh first = read_mesh(args.first).mesh;
  const Mesh second = read_mesh(args.second).mesh;
  progress.stage("joining the surfaces");
  const UnionResult u = surface_union(first, second);
  progress.stage("writing " + args.output);
  write_mesh(u.mesh, args.output, {.encoding = args.encoding, .vertex_fields = surface_fields(u.mesh)});
  progress.finish();
  if (args.json) {
    print_json(toml::table{{"first", args.first},
                           {"second", args.second},
                           {"output", args.output},
                           {"removed_faces_first", static_cast<int64_t>(u.removed_faces_a)},
                           {"removed_faces_second", static_cast<int64_t>(u.removed_faces_b)},
                           {"joined_loops", static_cast<int64_t>(u.joined_loops)},
                           {"vertices", static_cast<int64_t>(u.mesh.n_vertices())},
                           {"faces", static_cast<int64_t>(u.mesh.n_faces())}});
    return;
  }
  std::cout << fmt::format("union: removed {} faces of {} and {} of {}, joined {} loop pair(s); {} vertices, {} "
                           "faces; wrote {}\n",
                           u.removed_faces_a, args.first, u.removed_faces_b, args.second, u.joined_loops,
                           u.mesh.n_vertices(), u.mesh.n_faces(), args.output);
}

} // namespace

void add_union_verb(CLI::App& app)
{
  auto args = std::make_shared<UnionArguments>();
  CLI::App* verb = app.add_subcommand("union", "Join two intersecting closed surfaces into the boundary of their union");
  verb->add_option("first", args->first, "First closed surface")->required();
  verb->add_option("second", args->second, "Second closed surface")->required();
  add_output_option(*verb, args->output, "Output mesh file")->required();
  add_encoding_flags(*verb, args->encoding);
  add_json_flag(*verb, args->json);
  verb->callback([args] { run(*args); });
}

} // namespace sdflow::cli
