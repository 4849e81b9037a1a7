//! `sdflow union A B -o OUT`: the boundary of the union of two surfaces (Appendix B).

#include "verbs.h"

#include "sdflow/io/io.h"
#include "sdflow/log.h"
#include "sdflow/retri/surface_union.h"

#include <string>

namespace sdflow::cli {

void add_union_verb(CLI::App& app)
{
  struct Arguments {
    std::string first, second, output;
  };
  auto args = std::make_shared<Arguments>();
  CLI::App* verb = app.add_subcommand("union", "Join two intersecting surfaces into the boundary of their union (a surface with a boundary keeps it)");
  verb->add_option("first", args->first, "First surface (its inside: the side its normals point away from)")->required();
  verb->add_option("second", args->second, "Second surface")->required();
  verb->add_option("-o,--output", args->output, "Output mesh file")->required();
  verb->callback([args] {
    const UnionResult u = surface_union(read_mesh(args->first).mesh, read_mesh(args->second).mesh);
    write_mesh(u.mesh, args->output);
    logger().info("union: removed {} faces of {} and {} of {}, joined {} loop pair(s); {} vertices, {} faces written "
                  "to {}",
                  u.removed_faces_a, args->first, u.removed_faces_b, args->second, u.joined_loops,
                  u.mesh.n_vertices(), u.mesh.n_faces(), args->output);
  });
}

} // namespace sdflow::cli
