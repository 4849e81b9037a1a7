//! `sdflow axisymmetric`: the exact kinetics of surfaces of revolution, computed in 1-D by the
//! axisymmetric solver (toolbox/sdflow/axisymmetric/): event times, bodies, drift, time series.
//!   sdflow axisymmetric torus|capsule|dumbbell|sphere-mode|profile [shape options]
//!                       [--end-time T] [--max-displacement D] [--max-edge H] [--edges-per-radius N]
//!                       [--stop-at-first-event] [-o SERIES.csv] [--json]

#include "common_options.h"
#include "json_report.h"
#include "verbs.h"
#include "work_progress.h"

#include "sdflow/axisymmetric/evolution.h"
#include "sdflow/axisymmetric/initial_curves.h"
#include "sdflow/errors.h"
#include "sdflow/io/io.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <sstream>

namespace sdflow::cli {
namespace {

struct AxisymmetricArguments {
  std::string shape, profile, csv;
  double major = 6, minor = 3, length_ratio = 9, radius = 1, amplitude = 0.01;
  int degree = 2;
  DumbbellParameters dumbbell;
  double end_time = std::numeric_limits<double>::infinity();
  axisymmetric::EvolutionOptions options;
  bool first_event_only = false, json = false;
};

//! The default end: well past the events of the shapes' defaults, scaled as t ∝ size⁴.
double default_end_time(const AxisymmetricArguments& a)
{
  if (a.shape == "torus")
    return 2 * std::pow(a.minor, 4); // the R/r = 2 torus seals near r⁴ · 0.85
  if (a.shape == "sphere-mode")
    return a.degree == 2 ? 0.2 : 0.05;
  if (a.shape == "capsule")
    return 50 * std::pow(a.radius, 4);
  if (a.shape == "dumbbell")
    return 1;
  return std::numeric_limits<double>::infinity();
}

axisymmetric::GeneratingCurve start_curve(const AxisymmetricArguments& a)
{
  if (a.shape == "torus")
    return axisymmetric::torus(a.major, a.minor);
  if (a.shape == "capsule")
    return axisymmetric::capsule(a.length_ratio, a.radius);
  if (a.shape == "dumbbell")
    return axisymmetric::dumbbell(a.dumbbell);
  if (a.shape == "sphere-mode")
    return axisymmetric::sphere_mode(a.degree, a.amplitude);
  if (a.profile.empty())
    throw InvalidParameter("axisymmetric profile: give the profile file");
  return axisymmetric::read_profile(a.profile);
}

const char* kind_name(axisymmetric::EventKind kind)
{
  return kind == axisymmetric::EventKind::seal ? "seal" : "pinch-off";
}

void run(AxisymmetricArguments a)
{
  a.options.end_time = std::isfinite(a.end_time) ? a.end_time : default_end_time(a);
  if (!std::isfinite(a.options.end_time))
    throw InvalidParameter("axisymmetric profile: give --end-time");
  a.options.continue_after_event = !a.first_event_only;
  const axisymmetric::GeneratingCurve start = start_curve(a);
  std::ostringstream series;
  series << "time,area,volume,neck_radius,bodies,steps\n";
  long next_row = 0;
  a.options.observer = [&](const axisymmetric::Sample& s) {
    if (a.csv.empty() || s.steps < next_row)
      return;
    next_row = s.steps + 10; // every tenth step
    series << fmt::format("{},{},{},{},{},{}\n", s.time, s.area, s.volume,
                          std::isfinite(s.neck_radius) ? s.neck_radius : -1.0, s.bodies, s.steps);
  };
  WorkProgress progress("axisymmetric");
  progress.stage(fmt::format("evolving the {} to t = {:.6g}", a.shape, a.options.end_time));
  const axisymmetric::EvolutionResult r = axisymmetric::evolve(start, a.options);
  progress.finish();
  if (!a.csv.empty())
    write_atomically(a.csv, [&](std::ostream& out) { out << series.str(); });
  const double volume_change = (r.last.volume - r.initial_volume) / r.initial_volume;
  if (a.json) {
    toml::table root{{"shape", a.shape}, {"end_time", r.last.time}, {"steps", r.last.steps},
                     {"bodies", r.last.bodies}, {"volume", r.last.volume}, {"volume_change", volume_change},
                     {"area", r.last.area}};
    toml::array events;
    for (const auto& e : r.events)
      events.push_back(toml::table{{"kind", kind_name(e.kind)}, {"time", e.time},
                                   {"extrapolated_time", e.extrapolated_time}, {"z", e.z}});
    if (!r.events.empty())
      root.insert("event_time", r.events.front().extrapolated_time);
    root.insert("events", std::move(events));
    print_json(std::move(root));
    return;
  }
  for (const auto& e : r.events)
    std::cout << fmt::format("{} at t = {:.6g} (extrapolated t* = {:.6g}), z = {:.4g}\n", kind_name(e.kind), e.time,
                             e.extrapolated_time, e.z);
  if (r.events.empty())
    std::cout << "no pinch-off or seal\n";
  std::cout << fmt::format("t = {:.6g} after {} steps: {} bodies, area {:.6g}, volume {:.6g} ({:+.2e} relative)\n",
                           r.last.time, r.last.steps, r.last.bodies, r.last.area, r.last.volume, volume_change);
}

} // namespace

void add_axisymmetric_verb(CLI::App& app)
{
  auto a = std::make_shared<AxisymmetricArguments>();
  CLI::App* verb = app.add_subcommand(
      "axisymmetric", "Surface diffusion of a surface of revolution, in 1-D (a reference for the 3-D flow): event "
                      "times of pinch-offs and seals, bodies, volume drift");
  verb->add_option("shape", a->shape, "The surface of revolution: a catalogue shape or a profile file's")
      ->required()
      ->check(CLI::IsMember({"torus", "capsule", "dumbbell", "sphere-mode", "profile"}));
  verb->add_option("file", a->profile, "For profile: the generating curve, one \"r z\" point a line");
  verb->add_option("--major", a->major, "torus: radius R of the centre circle")->capture_default_str();
  verb->add_option("--minor", a->minor, "torus: tube radius r < R")->capture_default_str();
  verb->add_option("--length-ratio", a->length_ratio, "capsule: L/D, total length over diameter")
      ->capture_default_str();
  verb->add_option("--radius", a->radius, "capsule: radius a")->capture_default_str();
  verb->add_option("--sphere-radius", a->dumbbell.radius, "dumbbell: radius of the end spheres")
      ->capture_default_str();
  verb->add_option("--neck-width", a->dumbbell.neck_width, "dumbbell: width of the isthmus")->capture_default_str();
  verb->add_option("--separation", a->dumbbell.separation, "dumbbell: distance of the end spheres' centres")
      ->capture_default_str();
  verb->add_option("--degree", a->degree, "sphere-mode: l (2 or 3)")->capture_default_str();
  verb->add_option("--amplitude", a->amplitude, "sphere-mode: ε of 1 + ε P_l(cos θ)")->capture_default_str();
  verb->add_option("--end-time,--t-end", a->end_time, "End time (default: past the shape's events; --t-end: its older name)")
      ->check(CLI::PositiveNumber);
  verb->add_option("--max-displacement", a->options.max_displacement,
                   "Time accuracy: largest node motion a step, relative to the radius of curvature")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  verb->add_option("--max-edge", a->options.spacing.max_length, "Longest edge (default: 1/100 of the largest r)")
      ->check(CLI::PositiveNumber);
  verb->add_option("--edges-per-radius", a->options.spacing.edges_per_radius,
                   "Edges per radius of curvature where that is finer")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  verb->add_flag("--stop-at-first-event", a->first_event_only, "Stop at the first pinch-off or seal");
  verb->add_option(std::string(output_names) + ",--csv", a->csv,
                   "Write the time series (every tenth step) to this CSV file (--csv: its older name)");
  add_json_flag(*verb, a->json, "event_time is the first event's t*; keys documented in README.md");
  verb->callback([a] { run(*a); });
}

} // namespace sdflow::cli
