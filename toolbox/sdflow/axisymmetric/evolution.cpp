#include "sdflow/axisymmetric/evolution.h"

#include "sdflow/axisymmetric/step.h"
#include "sdflow/errors.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace sdflow::axisymmetric {
namespace {

constexpr double kGrowth = 1.25;  // largest growth of τ per accepted step
constexpr double kSafety = 0.8;   // aim below the displacement bound
constexpr double kMinTau = 1e-300;

//! A body being evolved, with the history of its neck for the extrapolation of t*.
struct Body {
  GeneratingCurve curve;
  std::vector<std::pair<double, double>> neck_history; //!< (t, r_neck)
  bool frozen = false; //!< a torus after its seal
};

//! Largest normal displacement of a node relative to the local radius of curvature (capped by the
//! curve's size). The scheme also slides nodes along the curve, toward the spacing it prefers,
//! by amounts that do not shrink with τ; that motion changes no shape and is not counted.
double displacement_ratio(const GeneratingCurve& before, const GeneratingCurve& after, double size)
{
  const std::vector<double> kappa = principal_curvature(before);
  const int n = before.node_count();
  double worst = 0;
  for (int k = 0; k < n; ++k) {
    const int prev = k > 0 ? k - 1 : (before.closed ? n - 1 : k);
    const int next = k + 1 < n ? k + 1 : (before.closed ? 0 : k);
    const Eigen::Vector2d chord = before.points[next] - before.points[prev];
    const Eigen::Vector2d normal = Eigen::Vector2d(chord.y(), -chord.x()).normalized();
    const double radius = std::min(size, kappa[k] > 0 ? 1 / kappa[k] : size);
    worst = std::max(worst, std::abs((after.points[k] - before.points[k]).dot(normal)) / radius);
  }
  return worst;
}

//! t* from r⁴ = a + b t fitted over the history's last stretch (radii below four times the last).
double extrapolated_time(const std::vector<std::pair<double, double>>& history)
{
  const double last = history.back().second;
  double n = 0, st = 0, sy = 0, stt = 0, sty = 0;
  for (auto it = history.rbegin(); it != history.rend() && it->second <= 4 * last; ++it) {
    const double y = std::pow(it->second, 4);
    n += 1;
    st += it->first;
    sy += y;
    stt += it->first * it->first;
    sty += it->first * y;
  }
  const double denominator = n * stt - st * st;
  if (n < 3 || !(std::abs(denominator) > 0))
    return history.back().first;
  const double slope = (n * sty - st * sy) / denominator, intercept = (sy - slope * st) / n;
  return slope < 0 ? -intercept / slope : history.back().first;
}

//! The two open curves an open curve becomes when node `neck` reaches the axis. The thin cone on
//! either side of the neck (radius below kCutRadius times the neck's) is closed off by a flat
//! end on the axis, which the flow rounds at once: continuing the cone down to the axis would
//! leave the step a cusp that only vanishing time steps resolve.
constexpr double kCutRadius = 3;

std::pair<GeneratingCurve, GeneratingCurve> cut(const GeneratingCurve& c, int neck)
{
  const double limit = kCutRadius * c.points[neck].x();
  int last_lower = neck, first_upper = neck;
  while (last_lower > 1 && c.points[last_lower].x() < limit)
    --last_lower;
  while (first_upper + 2 < c.node_count() && c.points[first_upper].x() < limit)
    ++first_upper;
  GeneratingCurve lower, upper;
  lower.points.assign(c.points.begin(), c.points.begin() + last_lower + 1);
  lower.points.emplace_back(0, lower.points.back().y());
  upper.points.emplace_back(0, c.points[first_upper].y());
  upper.points.insert(upper.points.end(), c.points.begin() + first_upper, c.points.end());
  return {lower, upper};
}

Sample sample_of(const std::vector<Body>& bodies, double time, long steps)
{
  Sample s{.time = time, .neck_radius = std::numeric_limits<double>::infinity(), .steps = steps};
  for (const Body& b : bodies) {
    s.area += surface_area(b.curve);
    s.volume += enclosed_volume(b.curve);
    ++s.bodies;
    if (const int neck = b.frozen ? -1 : neck_node(b.curve); neck >= 0)
      s.neck_radius = std::min(s.neck_radius, b.curve.points[neck].x());
  }
  return s;
}

//! One run at the options' max_displacement.
EvolutionResult evolve_once(const GeneratingCurve& start, const EvolutionOptions& options)
{
  if (!(options.max_displacement > 0) || !(options.stop_radius > 0) || !(options.end_time > 0) ||
      !(options.max_tau > 0) || options.max_steps < 1)
    throw InvalidParameter(fmt::format("axisymmetric flow: need max_displacement > 0 ({}), stop_radius > 0 ({}), "
                                       "end_time > 0 ({}), max_steps ≥ 1 ({})", options.max_displacement,
                                       options.stop_radius, options.end_time, options.max_steps));
  double size = 0;
  for (const auto& p : start.points)
    size = std::max(size, p.x());
  Spacing spacing = options.spacing;
  if (spacing.max_length == 0)
    spacing.max_length = size / 100;
  if (spacing.min_length == 0)
    spacing.min_length = size / 20000;
  const double stop_radius = options.stop_radius * size;

  EvolutionResult result;
  std::vector<Body> bodies{{.curve = redistribute(start, spacing)}};
  result.initial_volume = enclosed_volume(bodies[0].curve);
  result.initial_area = surface_area(bodies[0].curve);
  double time = 0, tau = 0;
  long steps = 0;
  bool stopped = false;
  while (!stopped && time < options.end_time * (1 - 1e-12)) {
    if (++steps > options.max_steps)
      throw SolverFailure(fmt::format("axisymmetric flow: more than {} steps before t = {}", options.max_steps,
                                      options.end_time));
    if (tau == 0) // a first step that moves nothing by more than about 1e-3 of its radius of curvature
      tau = std::pow(spacing.max_length, 4) * 1e-2;
    tau = std::min({tau, options.max_tau, options.end_time - time});
    // One step of every body with the same τ; a step that moves too far is retried with less.
    std::vector<GeneratingCurve> next;
    double worst = 0;
    for (;;) {
      next.clear();
      worst = 0;
      for (const Body& b : bodies) {
        if (b.frozen) {
          next.push_back(b.curve);
          continue;
        }
        next.push_back(diffusion_step(b.curve, tau).curve);
        worst = std::max(worst, displacement_ratio(b.curve, next.back(), size));
      }
      if (worst <= 2 * options.max_displacement)
        break;
      tau *= std::max(0.1, kSafety * options.max_displacement / worst);
      if (tau < kMinTau)
        throw SolverFailure(fmt::format("axisymmetric flow: the time step collapsed at t = {}", time));
    }
    time += tau;
    tau *= worst > 0 ? std::min(kGrowth, kSafety * options.max_displacement / worst) : kGrowth;

    std::vector<Body> after;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      Body b = bodies[i];
      b.curve = std::move(next[i]);
      if (b.frozen) {
        after.push_back(std::move(b));
        continue;
      }
      const int neck = neck_node(b.curve);
      if (neck >= 0)
        b.neck_history.emplace_back(time, b.curve.points[neck].x());
      if (neck >= 0 && b.curve.points[neck].x() < stop_radius) {
        Event event{.kind = b.curve.closed ? EventKind::seal : EventKind::pinch_off, .time = time,
                    .extrapolated_time = extrapolated_time(b.neck_history), .z = b.curve.points[neck].y()};
        result.events.push_back(event);
        stopped = !options.continue_after_event;
        if (b.curve.closed) {
          b.frozen = true;
          after.push_back(std::move(b));
        } else {
          auto [lower, upper] = cut(b.curve, neck);
          for (GeneratingCurve* piece : {&lower, &upper})
            if (piece->node_count() >= 3)
              after.push_back({.curve = redistribute(*piece, spacing)});
        }
        continue;
      }
      if (needs_redistribution(b.curve, spacing))
        b.curve = redistribute(b.curve, spacing);
      after.push_back(std::move(b));
    }
    bodies = std::move(after);
    if (std::all_of(bodies.begin(), bodies.end(), [](const Body& b) { return b.frozen; }))
      stopped = true;
    if (options.observer)
      options.observer(sample_of(bodies, time, steps));
  }
  for (const Body& b : bodies)
    result.bodies.push_back(b.curve);
  result.last = sample_of(bodies, time, steps);
  return result;
}

} // namespace

EvolutionResult evolve(const GeneratingCurve& start, const EvolutionOptions& options)
{
  check_curve(start);
  if (!options.richardson)
    return evolve_once(start, options);
  EvolutionOptions coarse_options = options;
  coarse_options.observer = nullptr;
  const EvolutionResult coarse = evolve_once(start, coarse_options);
  EvolutionOptions fine_options = options;
  fine_options.max_displacement /= 2;
  EvolutionResult fine = evolve_once(start, fine_options);
  if (coarse.events.size() == fine.events.size())
    for (std::size_t i = 0; i < fine.events.size(); ++i)
      fine.events[i].extrapolated_time = 2 * fine.events[i].extrapolated_time - coarse.events[i].extrapolated_time;
  return fine;
}

} // namespace sdflow::axisymmetric
