//! `sdflow normals MESH_OR_POINTS -o OUT.ply [--k 18]`: oriented point normals by jet fitting and
//! minimum-spanning-tree orientation; points whose orientation is inconsistent are removed.

#include "verbs.h"

#include "sdflow/io/point_cloud.h"
#include "sdflow/log.h"
#include "sdflow/reconstruct/point_normals.h"

#include <cmath>
#include <memory>
#include <string>

namespace sdflow::cli {
namespace {

struct NormalsArguments {
  std::string input;
  std::string output;
  PointNormalsOptions options;
  double agreement_degrees = 0;
  bool ascii = false;
};

} // namespace

void add_normals_verb(CLI::App& app)
{
  auto args = std::make_shared<NormalsArguments>();
  args->agreement_degrees = args->options.orientation.agreement_angle * 180 / M_PI;
  CLI::App* verb = app.add_subcommand(
      "normals", "Estimate oriented point normals (jet fitting, MST orientation) and write a PLY point cloud");
  verb->add_option("input", args->input, "Mesh or point file (OFF, OBJ, PLY, STL): its vertices are the points")
      ->required();
  verb->add_option("-o,--output", args->output, "Output point cloud (.ply with x y z nx ny nz)")->required();
  verb->add_option("--k", args->options.neighbours, "Neighbourhood size, the point itself included")
      ->capture_default_str()
      ->check(CLI::Range(6, 1000));
  verb->add_option("--agreement-angle", args->agreement_degrees,
                   "Degrees within which a neighbour's normal agrees with a point's")
      ->capture_default_str();
  verb->add_option("--min-agreement", args->options.orientation.min_agreement,
                   "Fraction of agreeing neighbours below which a point is removed")
      ->capture_default_str();
  verb->add_flag("--ascii", args->ascii, "Write ascii PLY instead of binary");
  verb->callback([args] {
    args->options.orientation.agreement_angle = args->agreement_degrees * M_PI / 180;
    const PointCloud input = read_point_cloud(args->input);
    const OrientedPoints oriented = oriented_point_normals(input.points, args->options);
    write_point_cloud({oriented.points, oriented.normals}, args->output,
                      args->ascii ? Encoding::ascii : Encoding::binary);
    logger().info("{}: {} points with oriented normals written to {}; {} removed as inconsistently oriented",
                  args->input, oriented.points.rows(), args->output, oriented.removed.size());
  });
}

} // namespace sdflow::cli
