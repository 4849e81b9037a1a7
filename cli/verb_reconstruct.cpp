//! `sdflow reconstruct POINTS.ply -o OUT [--json]`: advancing-front surface reconstruction of an
//! oriented point cloud (normals are estimated first when the file has none).

#include "common_options.h"
#include "json_report.h"
#include "neighbourhood_check.h"
#include "verbs.h"
#include "work_progress.h"

#include "sdflow/geometry/topology.h"
#include "sdflow/io/io.h"
#include "sdflow/io/point_cloud.h"
#include "sdflow/reconstruct/advancing_front.h"
#include "sdflow/reconstruct/point_normals.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <string>

namespace sdflow::cli {
namespace {

struct ReconstructArguments {
  std::string input;
  std::string output;
  ReconstructionOptions options;
  double beta_degrees = 0;
  double normal_degrees = 0;
  PointNormalsOptions normals;
  Encoding encoding = Encoding::binary;
  bool json = false;
};

void run(ReconstructArguments& args)
{
  args.options.beta = args.beta_degrees * M_PI / 180;
  args.options.max_normal_deviation = args.normal_degrees * M_PI / 180;
  WorkProgress progress("reconstruct");
  progress.stage("reading " + args.input);
  PointCloud cloud = read_point_cloud(args.input);
  const bool estimated = cloud.normals.rows() == 0;
  std::size_t removed = 0;
  if (estimated) {
    check_neighbourhood(cloud.points.rows(), args.normals.neighbours, args.input);
    progress.stage(fmt::format("estimating the normals of {} points", cloud.points.rows()));
    const OrientedPoints oriented = oriented_point_normals(cloud.points, args.normals);
    removed = oriented.removed.size();
    cloud = {oriented.points, oriented.normals};
  } else {
    // Files may store normals of any length; reconstruction wants unit ones.
    cloud.normals.rowwise().normalize();
  }
  progress.stage(fmt::format("reconstructing from {} points", cloud.points.rows()));
  const Reconstruction r = reconstruct_surface(cloud.points, cloud.normals, args.options);
  progress.stage("writing " + args.output);
  write_mesh(r.mesh, args.output, {.encoding = args.encoding, .vertex_fields = surface_fields(r.mesh)});
  progress.finish();
  int genus = 0, loops = 0;
  for (const auto& c : component_topology(r.mesh)) {
    genus += c.genus;
    loops += c.boundary_loops;
  }
  if (args.json) {
    print_json(toml::table{{"input", args.input},
                           {"output", args.output},
                           {"estimated_normals", estimated},
                           {"removed_points", static_cast<int64_t>(removed)},
                           {"points", static_cast<int64_t>(cloud.points.rows())},
                           {"unused_points", static_cast<int64_t>(r.unused.size())},
                           {"vertices", static_cast<int64_t>(r.mesh.n_vertices())},
                           {"faces", static_cast<int64_t>(r.mesh.n_faces())},
                           {"components", r.components},
                           {"genus", genus},
                           {"boundary_loops", loops}});
    return;
  }
  if (estimated)
    std::cout << fmt::format("{}: no normals in the file: estimated them, {} inconsistent points removed\n",
                             args.input, removed);
  std::cout << fmt::format("{}: {} triangles on {} of {} points ({} unused), {} component(s), total genus {}, {} "
                           "boundary loop(s); wrote {}\n",
                           args.input, r.mesh.n_faces(), r.mesh.n_vertices(), cloud.points.rows(), r.unused.size(),
                           r.components, genus, loops, args.output);
}

} // namespace

void add_reconstruct_verb(CLI::App& app)
{
  auto args = std::make_shared<ReconstructArguments>();
  args->beta_degrees = args->options.beta * 180 / M_PI;
  args->normal_degrees = args->options.max_normal_deviation * 180 / M_PI;
  CLI::App* verb = app.add_subcommand(
      "reconstruct", "Reconstruct an oriented surface from a point cloud (greedy Delaunay advancing front)");
  verb->add_option("points", args->input,
                   "Point cloud: PLY with x y z [nx ny nz], or any mesh file whose vertices are the points")
      ->required();
  add_output_option(*verb, args->output, fmt::format("Output mesh ({})", mesh_formats))->required();
  verb->add_option("--beta", args->beta_degrees, "Degrees of the wedge in which only the radius ranks candidates")
      ->capture_default_str();
  verb->add_option("--radius-ratio", args->options.radius_ratio_bound,
                   "Largest radius ratio of a candidate outside the wedge to its neighbour")
      ->capture_default_str();
  verb->add_option("--normal-deviation", args->normal_degrees,
                   "Largest angle in degrees between a triangle's normal and its points' normals")
      ->capture_default_str();
  verb->add_option("--neighbours,--k", args->normals.neighbours,
                   "k, the neighbourhood size when normals must be estimated (6 to 1000; --k: its older name)")
      ->capture_default_str()
      ->check(CLI::Range(6, 1000));
  add_encoding_flags(*verb, args->encoding);
  add_json_flag(*verb, args->json);
  verb->callback([args] { run(*args); });
}

} // namespace sdflow::cli
