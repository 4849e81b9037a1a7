#include "sdflow/flow/time_step.h"

#include "sdflow/errors.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

namespace sdflow {
namespace {

std::string trim(const std::string& s)
{
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos)
    return {};
  return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

template <typename T>
bool parse_number(const std::string& text, T& value)
{
  const std::string t = trim(text);
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
  return ec == std::errc() && end == t.data() + t.size();
}

TauSchedule read_csv_schedule(const std::filesystem::path& file, std::istream& in)
{
  std::vector<ScheduleEntry> entries;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    line = trim(line.substr(0, line.find('#')));
    if (line.empty())
      continue;
    std::vector<std::string> fields;
    std::stringstream ss(line);
    for (std::string field; std::getline(ss, field, ',');)
      fields.push_back(field);
    ScheduleEntry e;
    const bool ok = fields.size() == 3 && parse_number(fields[0], e.first_step) &&
                    parse_number(fields[1], e.last_step) && parse_number(fields[2], e.tau);
    if (!ok) {
      if (entries.empty() && !std::isdigit(static_cast<unsigned char>(line[0])))
        continue; // a header line
      throw IoError(fmt::format("{}:{}: expected `first_step,last_step,tau`, got `{}`", file.string(), number, line));
    }
    entries.push_back(e);
  }
  return TauSchedule(std::move(entries));
}

TauSchedule read_toml_schedule(const std::filesystem::path& file)
{
  toml::table table;
  try {
    table = toml::parse_file(file.string());
  } catch (const toml::parse_error& e) {
    throw IoError(fmt::format("{}:{}: {}", file.string(), e.source().begin.line, e.description()));
  }
  const toml::array* rows = table["schedule"].as_array();
  if (!rows)
    throw IoError(fmt::format("{}: no `schedule = [[first, last, tau], ...]` array", file.string()));
  std::vector<ScheduleEntry> entries;
  for (std::size_t i = 0; i < rows->size(); ++i) {
    const toml::array* row = rows->get(i)->as_array();
    const auto first = row && row->size() == 3 ? row->get(0)->value<long>() : std::nullopt;
    const auto last = row && row->size() == 3 ? row->get(1)->value<long>() : std::nullopt;
    const auto tau = row && row->size() == 3 ? row->get(2)->value<double>() : std::nullopt;
    if (!first || !last || !tau)
      throw IoError(fmt::format("{}: schedule entry {} is not [first_step, last_step, tau]", file.string(), i + 1));
    entries.push_back({*first, *last, *tau});
  }
  return TauSchedule(std::move(entries));
}

} // namespace

TauSchedule::TauSchedule(std::vector<ScheduleEntry> entries) : entries_(std::move(entries))
{
  if (entries_.empty())
    throw InvalidParameter("τ schedule: no entries");
  for (auto& e : entries_)
    if (e.first_step == 0)
      e.first_step = 1; // the paper's tables count from step 0
  std::sort(entries_.begin(), entries_.end(),
            [](const ScheduleEntry& a, const ScheduleEntry& b) { return a.first_step < b.first_step; });
  long expected = 1;
  for (const auto& e : entries_) {
    if (e.last_step < e.first_step)
      throw InvalidParameter(fmt::format("τ schedule: range {}-{} is reversed", e.first_step, e.last_step));
    if (!(e.tau > 0) || !std::isfinite(e.tau))
      throw InvalidParameter(fmt::format("τ schedule: steps {}-{} have τ = {} (must be positive)", e.first_step,
                                         e.last_step, e.tau));
    if (e.first_step != expected)
      throw InvalidParameter(fmt::format("τ schedule: {} at step {} (range {}-{} should start at {})",
                                         e.first_step < expected ? "overlap" : "gap", e.first_step, e.first_step,
                                         e.last_step, expected));
    expected = e.last_step + 1;
  }
}

double TauSchedule::tau_for_step(long step) const
{
  if (entries_.empty())
    throw InvalidParameter("τ schedule: empty");
  const auto it = std::lower_bound(entries_.begin(), entries_.end(), step,
                                   [](const ScheduleEntry& e, long s) { return e.last_step < s; });
  return it == entries_.end() ? entries_.back().tau : it->tau;
}

TauSchedule read_schedule(const std::filesystem::path& file)
{
  std::ifstream in(file);
  if (!in)
    throw IoError(fmt::format("{}: cannot open the τ schedule", file.string()));
  if (file.extension() == ".toml")
    return read_toml_schedule(file);
  return read_csv_schedule(file, in);
}

std::string StepCheck::describe() const
{
  std::vector<std::string> parts;
  if (non_finite)
    parts.emplace_back("non-finite positions");
  if (inverted_triangles > 0)
    parts.push_back(fmt::format("{} triangles turned over", inverted_triangles));
  if (displacement_exceeded)
    parts.push_back(fmt::format("normal displacement {:.3g} of the local edge length", displacement_ratio));
  if (volume_exceeded)
    parts.push_back(fmt::format("relative volume change {:.3g}", volume_change));
  if (error_exceeded)
    parts.push_back(fmt::format("local error estimate {:.3g} of the local edge length", error_estimate));
  if (energy_rose)
    parts.push_back(fmt::format("the energy rose by {:.3g} (relative)", energy_change));
  if (parts.empty())
    return "accepted";
  std::string text = parts.front();
  for (std::size_t i = 1; i < parts.size(); ++i)
    text += ", " + parts[i];
  return text;
}

void validate_time_step_options(const TimeStepOptions& o)
{
  const TimeStepRanges& r = time_step_ranges;
  const AdaptiveOptions& a = o.adaptive;
  check_in_range(r.tolerance, a.tolerance, "adaptive.tolerance");
  switch (o.mode) {
  case TimeStepMode::constant:
    check_in_range(r.tau, o.tau, "tau");
    return;
  case TimeStepMode::schedule:
    if (o.schedule.entries().empty())
      throw InvalidParameter("τ schedule mode without a schedule");
    check_in_range(r.schedule_retries, o.schedule_retries, "schedule_retries");
    break; // a table step that fails is covered by adaptive steps
  case TimeStepMode::adaptive:
    break;
  }
  check_in_range(r.initial_tau, a.initial_tau, "adaptive.initial_tau");
  check_in_range(r.max_displacement, a.max_displacement, "adaptive.max_displacement");
  check_in_range(r.growth, a.growth, "adaptive.growth");
  check_in_range(r.shrink, a.shrink, "adaptive.shrink");
  check_in_range(r.safety, a.safety, "adaptive.safety");
  check_in_range(r.max_volume_change, a.max_volume_change, "adaptive.max_volume_change");
  check_in_range(r.min_tau, a.min_tau, "adaptive.min_tau");
  check_in_range(r.max_tau, a.max_tau, "adaptive.max_tau");
  check_in_range(r.max_rejections, a.max_rejections, "adaptive.max_rejections");
  check_in_range(r.start_steps, a.start_steps, "adaptive.start_steps");
  check_in_range(r.start_damping, a.start_damping, "adaptive.start_damping");
  if (a.max_tau < a.min_tau)
    throw InvalidParameter(fmt::format("adaptive.max_tau ({}) must be at least adaptive.min_tau ({})", a.max_tau,
                                       a.min_tau));
}

TimeStepController::TimeStepController(const TimeStepOptions& options, TimeStepState state)
    : options_(options), state_(state)
{
  validate_time_step_options(options_);
}

double TimeStepController::propose(long step, double automatic_tau, double time_left)
{
  double tau = 0;
  if (adaptive()) {
    if (state_.next_tau == 0)
      state_.next_tau = options_.adaptive.initial_tau > 0 ? options_.adaptive.initial_tau : automatic_tau;
    if (!(state_.next_tau > 0) || !std::isfinite(state_.next_tau))
      throw InvalidParameter(fmt::format("adaptive τ: no usable initial τ (got {})", state_.next_tau));
    tau = std::clamp(state_.next_tau, options_.adaptive.min_tau, options_.adaptive.max_tau);
    // Covering a table step: its end is never passed, and a sliver of it is not left for later
    // (the whole rest is at most the growth bound 1.25 times the proposal).
    const double left = state_.fallback_left;
    if (left > 0 && (tau > left || left - tau < 0.25 * tau))
      tau = left;
  } else if (options_.mode == TimeStepMode::constant) {
    tau = options_.tau;
  } else {
    tau = std::ldexp(options_.schedule.tau_for_step(table_step(step)), -state_.rejections);
  }
  return std::min(tau, time_left);
}

bool TimeStepController::judge(long step, double tau, const StepCheck& check)
{
  if (adaptive()) {
    const bool covering = state_.fallback_left > 0;
    const bool accepted = judge_adaptive(step, tau, check);
    if (accepted && covering)
      cover_table_step(step, tau);
    return accepted;
  }
  if (!check.non_finite && check.inverted_triangles == 0 && !check.volume_exceeded) {
    state_.rejections = 0;
    return true;
  }
  const int retries = options_.mode == TimeStepMode::schedule ? options_.schedule_retries : 0;
  if (state_.rejections < retries) {
    ++state_.rejections;
    return false;
  }
  if (!check.non_finite && check.inverted_triangles == 0)
    throw TimeStepTooLarge(too_large(step, tau, check, retries));
  throw UnacceptableStep(fmt::format("step {} with τ = {:g} is unstable: {}{}. Use a smaller τ, β ≥ 1/2, {}or "
                                     "adaptive time steps", step, tau, check.describe(),
                                     retries > 0 ? fmt::format(" after {} halvings of the table's τ", retries) : "",
                                     options_.mode == TimeStepMode::schedule ? "schedule retries, " : ""),
                         check.failed_vertices);
}

//! Why a constant or tabled τ that broke the volume bound is too large, and by how much.
std::string TimeStepController::too_large(long step, double tau, const StepCheck& check, int retries) const
{
  const double bound = options_.adaptive.max_volume_change;
  std::string advice = "use adaptive time steps (--adaptive), or a smaller τ";
  if (check.adaptive_tau > 0 && check.adaptive_tau < tau)
    advice = fmt::format("the adaptive control would start from τ = {:.3g} on this surface, {:.3g} times smaller: use "
                         "adaptive time steps (--adaptive), or a τ of about that size",
                         check.adaptive_tau, tau / check.adaptive_tau);
  return fmt::format("step {}: τ = {:g} is too large for the scheme: the step changes the material volume of a "
                     "component (closed, or open with its boundary) by {:.3g} (relative), {:.3g} times the bound "
                     "of {:g} (adaptive.max_volume_change), so it is no approximation of the flow, which keeps volumes{}; {}",
                     step, tau, check.volume_change, check.volume_change / bound, bound,
                     retries > 0 ? fmt::format(" (also after {} halvings of the table's τ)", retries) : "", advice);
}

bool TimeStepController::judge_adaptive(long step, double tau, const StepCheck& check)
{
  const AdaptiveOptions& a = options_.adaptive;
  // The factors that would bring each bounded quantity to `safety` times its bound.
  const double displacement_factor =
      check.displacement_ratio > 0 ? a.safety * a.max_displacement / check.displacement_ratio : a.growth;
  const double error_factor = a.tolerance > 0 && check.error_estimate > 0
                                  ? a.safety * std::sqrt(a.tolerance / check.error_estimate)
                                  : a.growth;
  energy_stood_aside_.reset();
  const double proposed = std::min(a.max_tau, tau * std::min({a.growth, displacement_factor, error_factor}));
  // A rise of the energy that does not fall with τ as the time step's would (whether or not it is
  // still above round-off): a rate of the semi-discrete flow where the mesh no longer resolves it.
  // The rule stands aside for this step, and the next goes on from what the first trial, which
  // failed on the energy alone, would have proposed: τ neither creeps down nor stays put.
  const bool others_kept = !check.non_finite && check.inverted_triangles == 0 && !check.displacement_exceeded &&
                           !check.volume_exceeded && !check.error_exceeded;
  const bool energy_rate = others_kept && energy_rejected_tau_ > tau && check.energy_change > 0 &&
                           check.energy_change > kEnergyRateShare * energy_rejected_rise_ *
                                                     std::pow(tau / energy_rejected_tau_, 1.5);
  if (!check.failed() || energy_rate) {
    state_.rejections = 0;
    state_.next_tau = proposed;
    if (energy_rate) {
      energy_stood_aside_ = EnergyStandAside{energy_rejected_tau_, energy_rejected_rise_, tau, check.energy_change};
      state_.next_tau = std::max(proposed, energy_rejected_next_tau_);
    }
    energy_rejected_tau_ = 0;
    if (tau >= state_.turning_since_tau)
      state_.turning_since_tau = 0;
    return true;
  }
  if (others_kept && check.energy_rose && energy_rejected_tau_ == 0) {
    energy_rejected_tau_ = tau;
    energy_rejected_rise_ = check.energy_change;
    energy_rejected_next_tau_ = proposed;
  }
  ++state_.rejections;
  if (check.inverted_triangles > 0 && state_.turning_since_tau == 0)
    state_.turning_since_tau = tau;
  double factor = a.shrink;
  if (check.displacement_exceeded)
    factor = std::min(factor, displacement_factor);
  if (check.error_exceeded)
    factor = std::min(factor, error_factor);
  state_.next_tau = tau * factor;
  if (state_.rejections > a.max_rejections || state_.next_tau < a.min_tau)
    throw UnacceptableStep(fmt::format("step {}: unstable, no acceptable τ after {} rejections (last τ = {:g}: {})",
                                       step, state_.rejections, tau, check.describe()),
                           check.failed_vertices);
  return false;
}

bool TimeStepController::turning_collapsed() const
{
  return adaptive() && state_.turning_since_tau > 0 && state_.next_tau < kTurningCollapse * state_.turning_since_tau;
}

//! An accepted adaptive step of `tau` covered part of a table step: the table's count stays put
//! until the table step is covered, then the next table step is covered too while its τ is beyond
//! the adaptive rule's.
void TimeStepController::cover_table_step(long step, double tau)
{
  state_.fallback_left -= tau;
  if (state_.fallback_left > 0) {
    ++state_.table_lag;
    return;
  }
  const double next_table_tau = options_.schedule.tau_for_step(table_step(step + 1));
  state_.fallback_left = state_.next_tau < next_table_tau ? next_table_tau : 0;
}

void TimeStepController::fall_back_to_adaptive(long step)
{
  if (options_.mode != TimeStepMode::schedule)
    throw InvalidParameter("only a τ schedule falls back to adaptive steps");
  state_.fallback_left = options_.schedule.tau_for_step(table_step(step));
  state_.next_tau = 0;
  state_.rejections = 0;
}

StepCheck check_trial(const TrialMotion& trial, const AdaptiveOptions& bounds, bool adaptive)
{
  StepCheck c;
  if (!trial.next.allFinite()) {
    c.non_finite = true;
    return c;
  }
  c.displacement_ratio = (trial.tau * trial.w.cwiseAbs()).cwiseQuotient(trial.edge_lengths).maxCoeff();
  if (trial.error.rows() > 0)
    c.error_estimate = trial.error.rowwise().norm().cwiseQuotient(trial.edge_lengths).maxCoeff();
  for (Eigen::Index f = 0; f < trial.triangles.rows(); ++f) {
    const auto normal = [&](const VertexVectors& x) {
      const Eigen::Vector3d a = x.row(trial.triangles(f, 0)), b = x.row(trial.triangles(f, 1)),
                            d = x.row(trial.triangles(f, 2));
      return Eigen::Vector3d((b - a).cross(d - a));
    };
    if (normal(trial.now).dot(normal(trial.next)) <= 0) {
      ++c.inverted_triangles;
      for (int k = 0; k < 3; ++k)
        c.failed_vertices.push_back(trial.triangles(f, k));
    }
  }
  c.volume_change = trial.volume_change;
  c.volume_exceeded = c.volume_change > bounds.max_volume_change;
  c.energy_change = trial.energy_change;
  if (adaptive) {
    c.energy_rose = c.energy_change > kEnergyRoundOff;
    c.displacement_exceeded = c.displacement_ratio > bounds.max_displacement;
    c.error_exceeded = bounds.tolerance > 0 && c.error_estimate > bounds.tolerance;
    if (c.displacement_exceeded)
      for (Eigen::Index v = 0; v < trial.w.size(); ++v)
        if (trial.tau * std::abs(trial.w[v]) > bounds.max_displacement * trial.edge_lengths[v])
          c.failed_vertices.push_back(static_cast<int>(v));
  }
  std::sort(c.failed_vertices.begin(), c.failed_vertices.end()); // not std::ranges: clang with GCC 12's library rejects ranges::unique
  c.failed_vertices.erase(std::unique(c.failed_vertices.begin(), c.failed_vertices.end()), c.failed_vertices.end());
  return c;
}

double start_tau(const AdaptiveOptions& options, double edge_length)
{
  return options.start_damping * std::pow(edge_length / std::numbers::pi, 4);
}

std::vector<bool> resolved_vertices(const Eigen::VectorXd& explicit_speed, const std::vector<bool>& held,
                                    const Eigen::VectorXd& edge_lengths)
{
  std::vector<bool> resolved(static_cast<std::size_t>(explicit_speed.size()), false);
  for (Eigen::Index v = 0; v < explicit_speed.size(); ++v)
    resolved[v] = (held.empty() || !held[v]) && explicit_speed[v] * std::pow(edge_lengths[v], 3) <= kUnresolvedVariation;
  return resolved;
}

double resolved_displacement_ratio(double tau, const Eigen::VectorXd& w, const Eigen::VectorXd& edge_lengths,
                                   const std::vector<bool>& resolved)
{
  double ratio = 0;
  for (Eigen::Index v = 0; v < w.size(); ++v)
    if (resolved[v])
      ratio = std::max(ratio, tau * std::abs(w[v]) / edge_lengths[v]);
  return ratio;
}

bool is_start_step(const AdaptiveOptions& options, long step, const std::vector<bool>& resolved,
                   const std::vector<bool>& held)
{
  if (step > options.start_steps)
    return false;
  for (std::size_t v = 0; v < resolved.size(); ++v)
    if (!resolved[v] && (held.empty() || !held[v]))
      return true;
  return false;
}

void TimeStepController::accept_start_step(double tau)
{
  state_.rejections = 0;
  state_.next_tau = tau;
}

double automatic_tau(const Eigen::VectorXd& explicit_speed, const std::vector<bool>& held,
                     const Eigen::VectorXd& edge_lengths, const AdaptiveOptions& options)
{
  double tau = std::numeric_limits<double>::infinity();
  for (Eigen::Index v = 0; v < explicit_speed.size(); ++v)
    if (explicit_speed[v] > 0 && (held.empty() || !held[v]))
      tau = std::min(tau, edge_lengths[v] / explicit_speed[v]);
  if (std::isinf(tau))
    return std::pow(edge_lengths.mean(), 4);
  return options.safety * options.max_displacement * tau;
}

} // namespace sdflow
