//! \file schema_time_step.cpp
//! \brief The run schema's sections on time steps: the mode, τ, the table, and the adaptive rule
//! (flow/time_step.h).

#include "sdflow/run/detail/schema_sections.h"

#include "sdflow/errors.h"

#include <fmt/format.h>

namespace sdflow::detail {
namespace {

bool adaptive_steps(const RunParameters& p) { return p.time_step.mode == TimeStepMode::adaptive; }

const char* mode_name(TimeStepMode mode)
{
  switch (mode) {
  case TimeStepMode::constant: return "constant";
  case TimeStepMode::schedule: return "schedule";
  case TimeStepMode::adaptive: break;
  }
  return "adaptive";
}

} // namespace

//! The time-step mode, a constant τ, a τ table.
void add_time_step_entries(std::vector<ParameterEntry>& s)
{
  {
    auto& e = add(s, entry("time_step", "--time-step", ParameterType::choice,
                           "`adaptive` (the default; its rule is set by the `[adaptive]` keys), `constant` "
                           "(needs `tau`) or `schedule` (needs `schedule`); a `tau` or `schedule` implies its mode"));
    e.choices = {"adaptive", "constant", "schedule"};
    e.order = ParameterEntry::Order::last;
    e.get = [](const RunParameters& p) -> ParameterValue { return std::string(mode_name(p.time_step.mode)); };
    e.set = [](RunParameters& p, const ParameterValue& v) {
      const std::string& mode = std::get<std::string>(v);
      if (mode == "constant") p.time_step.mode = TimeStepMode::constant;
      else if (mode == "schedule") p.time_step.mode = TimeStepMode::schedule;
      else if (mode == "adaptive") p.time_step.mode = TimeStepMode::adaptive;
      else
        throw InvalidParameter(fmt::format("time_step must be \"constant\", \"schedule\" or \"adaptive\", got \"{}\"",
                                           mode));
    };
    e.shorthands = {{"--adaptive", "adaptive", "Adaptive τ (the default): --time-step adaptive"}};
    e.meshlab = {.name = "AutomaticTau", .label = "Automatic time step",
                 .help = "On: τ is chosen for each step, as sdflow's adaptive time step does. It starts from a safe "
                         "estimate, grows while the surface evolves calmly, and a step is retried with a smaller τ "
                         "if a vertex would move too far for its edges, a triangle would flip, or a volume would "
                         "drift.<br>Off: every step uses the time step τ below.",
                 .boolean_choices = std::pair<std::string, std::string>{"constant", "adaptive"}};
  }
  {
    auto& e = add(s, entry("tau", "--tau", ParameterType::real, "Constant time step τ (implies time_step = constant)"));
    e.range = time_step_ranges.tau;
    e.get = [](const RunParameters& p) -> ParameterValue { return p.time_step.tau; };
    e.set = [](RunParameters& p, const ParameterValue& v) { p.time_step.tau = std::get<double>(v); };
    e.implies = {{"time_step", std::string("constant")}};
    e.in_use = e.written = [](const RunParameters& p) { return p.time_step.mode == TimeStepMode::constant; };
    e.meshlab = {.name = "Tau", .label = "Time step τ",
                 .help = "The constant time step, used only when the automatic time step is off (> 0). Surface "
                         "diffusion is a fourth-order flow: stable steps scale like h⁴ for edge length h. The "
                         "default is h⁴ for this mesh's mean edge length.",
                 .source = MeshlabParameter::Default::natural_time_step};
  }
  {
    auto& e = add(s, entry("schedule", "--schedule", ParameterType::schedule,
                           "τ table like the paper's Tables 1–3: a file (CSV `first_step,last_step,tau`, or TOML) or, in "
                           "a scenario, inline `[[1, 50, 0.01], [51, 100, 0.02]]` (implies time_step = schedule)"));
    e.existing_file = true;
    e.get = [](const RunParameters& p) -> ParameterValue {
      return ScheduleSetting{p.time_step.schedule_file, p.time_step.schedule.entries()};
    };
    e.set = [](RunParameters& p, const ParameterValue& v) {
      const auto& schedule = std::get<ScheduleSetting>(v);
      p.time_step.schedule = TauSchedule(schedule.entries);
      p.time_step.schedule_file = schedule.file;
    };
    e.implies = {{"time_step", std::string("schedule")}};
    e.written = [](const RunParameters& p) { return p.time_step.mode == TimeStepMode::schedule; };
  }
  {
    auto& e = add(s, entry("schedule_retries", "--schedule-retries", ParameterType::integer,
                           "Halvings of the table's τ allowed for a step that turns triangles over (0: stop)"));
    e.range = time_step_ranges.schedule_retries;
    bind<long>(e, &RunParameters::time_step, &TimeStepOptions::schedule_retries);
    e.in_use = e.written = [](const RunParameters& p) { return p.time_step.mode == TimeStepMode::schedule; };
  }
}

//! [adaptive]: the adaptive time step (flow/time_step.h).
void add_adaptive_entries(std::vector<ParameterEntry>& s)
{
  const auto adaptive = [&](const char* key, const char* flag, ParameterType type, ParameterRange range,
                            const char* help) -> ParameterEntry& {
    auto& e = add(s, entry(key, flag, type, help));
    e.range = range;
    e.in_use = adaptive_steps;
    return e;
  };
  bind<double>(adaptive("adaptive.initial_tau", "--initial-tau", ParameterType::real, time_step_ranges.initial_tau,
                        "Adaptive τ: the first step's τ (0: automatic, from ΔH and the edge lengths)"),
               &RunParameters::time_step, &TimeStepOptions::adaptive, &AdaptiveOptions::initial_tau);
  bind<double>(adaptive("adaptive.max_displacement", "--max-displacement", ParameterType::real, time_step_ranges.max_displacement,
                        "Adaptive τ: bound on a step's normal displacement, relative to the local edge length"),
               &RunParameters::time_step, &TimeStepOptions::adaptive, &AdaptiveOptions::max_displacement);
  bind<double>(adaptive("adaptive.growth", "--tau-growth", ParameterType::real, time_step_ranges.growth,
                        "Adaptive τ: largest growth factor of τ per accepted step"),
               &RunParameters::time_step, &TimeStepOptions::adaptive, &AdaptiveOptions::growth);
  bind<double>(adaptive("adaptive.shrink", "--tau-shrink", ParameterType::real, time_step_ranges.shrink,
                        "Adaptive τ: factor applied to τ on a rejected step"),
               &RunParameters::time_step, &TimeStepOptions::adaptive, &AdaptiveOptions::shrink);
  bind<double>(adaptive("adaptive.safety", "--tau-safety", ParameterType::real, time_step_ranges.safety,
                        "Adaptive τ: aim this fraction of the bounds when predicting the next τ"),
               &RunParameters::time_step, &TimeStepOptions::adaptive, &AdaptiveOptions::safety);
  bind<double>(adaptive("adaptive.max_volume_change", "--max-volume-change", ParameterType::real, time_step_ranges.max_volume_change,
                        "Adaptive τ: bound on a component's relative change of material volume per step"),
               &RunParameters::time_step, &TimeStepOptions::adaptive, &AdaptiveOptions::max_volume_change);
  bind<double>(adaptive("adaptive.min_tau", "--min-tau", ParameterType::real, time_step_ranges.min_tau,
                        "Adaptive τ: below this τ the run is declared unstable"),
               &RunParameters::time_step, &TimeStepOptions::adaptive, &AdaptiveOptions::min_tau);
  bind<double>(adaptive("adaptive.max_tau", "--max-tau", ParameterType::real, time_step_ranges.max_tau,
                        "Adaptive τ: the largest τ (inf: none)"),
               &RunParameters::time_step, &TimeStepOptions::adaptive, &AdaptiveOptions::max_tau);
  bind<long>(adaptive("adaptive.max_rejections", "--max-rejections", ParameterType::integer, time_step_ranges.max_rejections,
                      "Adaptive τ: rejected trials in a row before the run is declared unstable"),
             &RunParameters::time_step, &TimeStepOptions::adaptive, &AdaptiveOptions::max_rejections);
  {
    auto& e = adaptive("adaptive.start_steps", "--start-steps", ParameterType::integer, time_step_ranges.start_steps,
                       "Adaptive τ: a run's first steps that may be start steps, whose τ_s = start_damping·(ℓ/π)⁴ "
                       "damps what the mesh does not resolve (noise, sharp edges, creases) when that, not the "
                       "resolved scales, would set τ; the first step on each new triangulation may be one too, "
                       "of at most the rule's τ (0: none)");
    bind<long>(e, &RunParameters::time_step, &TimeStepOptions::adaptive, &AdaptiveOptions::start_steps);
    e.paper = 0L;
  }
  bind<double>(adaptive("adaptive.start_damping", "--start-damping", ParameterType::real, time_step_ranges.start_damping,
                        "Adaptive τ: a start step's τ_s·(π/ℓ)⁴, the damping of the wavelength 2ℓ per start step"),
               &RunParameters::time_step, &TimeStepOptions::adaptive, &AdaptiveOptions::start_damping);
  {
    auto& e = adaptive("adaptive.tolerance", "--tolerance", ParameterType::real, time_step_ranges.tolerance,
                       "Adaptive τ: bound on the extrapolated step's local error estimate, relative to the local "
                       "edge length (0: off); needs extrapolated steps, which the flag implies");
    e.in_use = nullptr; // checked in every mode, like its need for extrapolated steps
    e.implies = {{"extrapolate", true, true}};
    bind<double>(e, &RunParameters::time_step, &TimeStepOptions::adaptive, &AdaptiveOptions::tolerance);
    e.paper = 0.0;
  }
}

} // namespace sdflow::detail
