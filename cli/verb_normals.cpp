//! `sdflow normals MESH_OR_POINTS -o OUT.ply [--neighbours 18] [--json]`: oriented point normals by
//! jet fitting and minimum-spanning-tree orientation; points whose orientation is inconsistent are
//! removed.

#include "common_options.h"
#include "json_report.h"
#include "neighbourhood_check.h"
#include "verbs.h"
#include "work_progress.h"

#include "sdflow/io/point_cloud.h"
#include "sdflow/reconstruct/point_normals.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <string>

namespace sdflow::cli {
namespace {

struct NormalsArguments {
  std::string input;
  std::string output;
  PointNormalsOptions options;
  double agreement_degrees = 0;
  Encoding encoding = Encoding::binary;
  bool json = false;
};

void run(NormalsArguments& args)
{
  args.options.orientation.agreement_angle = args.agreement_degrees * M_PI / 180;
  WorkProgress progress("normals");
  progress.stage("reading " + args.input);
  const PointCloud input = read_point_cloud(args.input);
  check_neighbourhood(input.points.rows(), args.options.neighbours, args.input);
  progress.stage(fmt::format("fitting and orienting the normals of {} points", input.points.rows()));
  const OrientedPoints oriented = oriented_point_normals(input.points, args.options);
  progress.stage("writing " + args.output);
  write_point_cloud({oriented.points, oriented.normals}, args.output, args.encoding);
  progress.finish();
  if (args.json) {
    print_json(toml::table{{"input", args.input},
                           {"output", args.output},
                           {"input_points", static_cast<int64_t>(input.points.rows())},
                           {"points", static_cast<int64_t>(oriented.points.rows())},
                           {"removed", static_cast<int64_t>(oriented.removed.size())}});
    return;
  }
  std::cout << fmt::format("{}: {} points with oriented normals, {} removed as inconsistently oriented; wrote {}\n",
                           args.input, oriented.points.rows(), oriented.removed.size(), args.output);
}

} // namespace

void add_normals_verb(CLI::App& app)
{
  auto args = std::make_shared<NormalsArguments>();
  args->agreement_degrees = args->options.orientation.agreement_angle * 180 / M_PI;
  CLI::App* verb = app.add_subcommand(
      "normals", "Estimate oriented point normals (jet fitting, MST orientation) and write a PLY point cloud");
  verb->add_option("input", args->input, fmt::format("Mesh or point file ({}): its vertices are the points", mesh_formats))
      ->required();
  add_output_option(*verb, args->output, "Output point cloud (.ply with x y z nx ny nz)")->required();
  verb->add_option("--neighbours,--k", args->options.neighbours,
                   "k, the neighbourhood size, the point itself included (6 to 1000; --k: its older name)")
      ->capture_default_str()
      ->check(CLI::Range(6, 1000));
  verb->add_option("--agreement-angle", args->agreement_degrees,
                   "Degrees within which a neighbour's normal agrees with a point's (above 0, below 180)")
      ->capture_default_str()
      ->check(CLI::Validator(
          [](std::string& text) {
            const double degrees = std::strtod(text.c_str(), nullptr);
            return degrees > 0 && degrees < 180 ? std::string() : "must be above 0 and below 180 degrees, got " + text;
          },
          "", ""));
  verb->add_option("--min-agreement", args->options.orientation.min_agreement,
                   "Fraction of agreeing neighbours below which a point is removed (0 to 1)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  add_encoding_flags(*verb, args->encoding);
  add_json_flag(*verb, args->json);
  verb->callback([args] { run(*args); });
}

} // namespace sdflow::cli
