//! `sdflow reconstruct POINTS.ply -o OUT`: advancing-front surface reconstruction of an oriented
//! point cloud (normals are estimated first when the file has none).

#include "verbs.h"

#include "sdflow/geometry/topology.h"
#include "sdflow/io/io.h"
#include "sdflow/io/point_cloud.h"
#include "sdflow/log.h"
#include "sdflow/reconstruct/advancing_front.h"
#include "sdflow/reconstruct/point_normals.h"

#include <cmath>
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
  bool binary = false;
};

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
  verb->add_option("-o,--output", args->output, "Output mesh (OFF, OBJ, PLY, STL)")->required();
  verb->add_option("--beta", args->beta_degrees, "Degrees of the wedge in which only the radius ranks candidates")
      ->capture_default_str();
  verb->add_option("--radius-ratio", args->options.radius_ratio_bound,
                   "Largest radius ratio of a candidate outside the wedge to its neighbour")
      ->capture_default_str();
  verb->add_option("--normal-deviation", args->normal_degrees,
                   "Largest angle in degrees between a triangle's normal and its points' normals")
      ->capture_default_str();
  verb->add_option("--k", args->normals.neighbours, "Neighbourhood size when normals must be estimated")
      ->capture_default_str()
      ->check(CLI::Range(6, 1000));
  verb->add_flag("--binary", args->binary, "Write binary PLY or STL");
  verb->callback([args] {
    args->options.beta = args->beta_degrees * M_PI / 180;
    args->options.max_normal_deviation = args->normal_degrees * M_PI / 180;
    PointCloud cloud = read_point_cloud(args->input);
    if (cloud.normals.rows() == 0) {
      const OrientedPoints oriented = oriented_point_normals(cloud.points, args->normals);
      logger().info("{}: no normals in the file: estimated them, {} inconsistent points removed", args->input,
                    oriented.removed.size());
      cloud = {oriented.points, oriented.normals};
    } else {
      // Files may store normals of any length; reconstruction wants unit ones.
      cloud.normals.rowwise().normalize();
    }
    const Reconstruction r = reconstruct_surface(cloud.points, cloud.normals, args->options);
    write_mesh(r.mesh, args->output, {.encoding = args->binary ? Encoding::binary : Encoding::ascii,
                                      .vertex_fields = surface_fields(r.mesh)});
    int genus = 0, loops = 0;
    for (const auto& c : component_topology(r.mesh)) {
      genus += c.genus;
      loops += c.boundary_loops;
    }
    logger().info("{}: {} triangles on {} of {} points ({} unused), {} component(s), total genus {}, {} boundary "
                  "loop(s), written to {}",
                  args->input, r.mesh.n_faces(), r.mesh.n_vertices(), cloud.points.rows(), r.unused.size(),
                  r.components, genus, loops, args->output);
  });
}

} // namespace sdflow::cli
