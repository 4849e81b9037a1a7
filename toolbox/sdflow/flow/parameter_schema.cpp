#include "sdflow/flow/parameter_schema.h"

#include "sdflow/errors.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <type_traits>

namespace sdflow {
namespace {


using Order = ParameterEntry::Order;

//! Get and set through a chain of members, p.*a.*b...; the value is held as `Value` (an int field
//! as a long), converted back on setting.
template <typename Value, typename... Members>
void bind(ParameterEntry& e, Members... chain)
{
  e.get = [=](const RunParameters& p) -> ParameterValue { return static_cast<Value>((p.*....*chain)); };
  e.set = [=](RunParameters& p, const ParameterValue& v) {
    auto& field = (p.*....*chain);
    field = static_cast<std::remove_reference_t<decltype(field)>>(std::get<Value>(v));
  };
}

ParameterEntry entry(std::string key, std::string flag, ParameterType type, std::string help)
{
  ParameterEntry e;
  e.key = std::move(key);
  e.flag = std::move(flag);
  e.type = type;
  e.help = std::move(help);
  return e;
}

ParameterRange at_least(double min) { return {.min = min}; }
ParameterRange above(double min) { return {.min = min, .min_open = true}; }

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

std::string number_text(double v)
{
  if (std::isinf(v))
    return v > 0 ? "∞" : "−∞";
  return fmt::format("{}", v);
}

std::vector<ParameterEntry> build_schema()
{
  std::vector<ParameterEntry> s;
  const auto add = [&s](ParameterEntry e) -> ParameterEntry& { return s.emplace_back(std::move(e)); };

  // --- What runs, where, and until when ---
  {
    auto& e = add(entry("preset", "--preset", ParameterType::choice,
                        "`paper`: the paper's scheme exactly (eq. 9 H, Voronoi areas, plain steps, its boundary rule, "
                        "uniform re-triangulation ℓ, flat projection, no volume restoration, no start steps, "
                        "whole-surface re-triangulation); "
                        "`default`: sdflow's. Applied before the other keys and flags, which override it"));
    e.choices = {"paper", "default"};
    e.order = Order::first;
    e.get = [](const RunParameters&) -> ParameterValue { return std::string(); };
    e.set = [](RunParameters& p, const ParameterValue& v) { apply_preset(std::get<std::string>(v), p); };
    e.written = [](const RunParameters&) { return false; }; // run.toml holds what it resolved to
  }
  {
    auto& e = add(entry("input", "--input", ParameterType::path, "The initial mesh (OFF, OBJ, PLY, STL, VTP)"));
    e.existing_file = true;
    bind<std::filesystem::path>(e, &RunParameters::input);
    e.written = [](const RunParameters& p) { return !p.input.empty(); };
  }
  {
    auto& e = add(entry("repair", "--repair", ParameterType::boolean,
                        "Repair the input when it is not a valid mesh, as `sdflow repair` does (duplicate vertices, "
                        "degenerate and repeated faces, non-manifold edges and vertices, orientation), before the run"));
    bind<bool>(e, &RunParameters::repair);
  }
  {
    auto& e = add(entry("out", "--out", ParameterType::path, "The run directory (must not hold a run yet)"));
    e.flag_aliases = {"-o", "--output"}; // the output's names on every verb
    bind<std::filesystem::path>(e, &RunParameters::output_dir);
    e.written = [](const RunParameters& p) { return !p.output_dir.empty(); };
  }
  {
    auto& e = add(entry("steps", "--steps", ParameterType::integer, "Stop after this many steps (0: no limit)"));
    e.range = at_least(0);
    e.resumable = true;
    e.meshlab = {.name = "Steps", .label = "Steps",
                 .help = "Number of time steps to take. Each accepted step advances the time by its time step τ.",
                 .value = ParameterValue(10L), .range = at_least(1)};
    bind<long>(e, &RunParameters::steps);
  }
  {
    auto& e = add(entry("end_time", "--end-time", ParameterType::real, "Stop at this time (absent: no limit)"));
    e.key_aliases = {"t_end"};
    e.flag_aliases = {"--t-end"};
    e.range = {.min = 0, .min_open = true, .infinite_allowed = true};
    e.resumable = true;
    bind<double>(e, &RunParameters::end_time);
    e.written = [](const RunParameters& p) { return std::isfinite(p.end_time); };
  }
  {
    auto& e = add(entry("stop_at_topology_change", "--stop-at-topology-change", ParameterType::boolean,
                        "Also stop after the first step that changes the component count or the genus (a pinch-off, "
                        "a seal, a fusion; with re-triangulation): for measuring event times"));
    e.resumable = true;
    bind<bool>(e, &RunParameters::stop_at_topology_change);
  }

  // --- Time steps ---
  {
    auto& e = add(entry("time_step", "--time-step", ParameterType::choice,
                        "`adaptive` (the default; its rule is set by the `[adaptive]` keys), `constant` "
                        "(needs `tau`) or `schedule` (needs `schedule`); a `tau` or `schedule` implies its mode"));
    e.choices = {"adaptive", "constant", "schedule"};
    e.order = Order::last;
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
    auto& e = add(entry("tau", "--tau", ParameterType::real, "Constant time step τ (implies time_step = constant)"));
    e.range = above(0);
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
    auto& e = add(entry("schedule", "--schedule", ParameterType::schedule,
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
    auto& e = add(entry("schedule_retries", "--schedule-retries", ParameterType::integer,
                        "Halvings of the table's τ allowed for a step that turns triangles over (0: stop)"));
    e.range = {.min = 0, .max = 60};
    bind<long>(e, &RunParameters::time_step, &TimeStepOptions::schedule_retries);
    e.in_use = e.written = [](const RunParameters& p) { return p.time_step.mode == TimeStepMode::schedule; };
  }

  // --- The scheme ---
  {
    auto& e = add(entry("beta", "--beta", ParameterType::real, "Implicitness β of eq. (6): 0.5 the paper's, 0 explicit"));
    e.range = at_least(0);
    e.meshlab = {.name = "Beta", .label = "Implicitness β",
                 .help = "Weight of the implicit part of the scheme (I + τβΔ²) w = ΔH: 0.5 is the paper's stable "
                         "choice, 0 the explicit scheme (which needs much smaller τ)."};
    bind<double>(e, &RunParameters::scheme, &SchemeOptions::beta);
  }
  {
    auto& e = add(entry("curvature", "--curvature", ParameterType::choice,
                        "Mean curvature: `cotangent` (H = ½ N·ΔX, converges), `normal_integral` (eq. 9, the paper's) "
                        "or `normal_integral_angle_sum` (eq. 9 over the angle sum, not 2π)"));
    e.choices = {"cotangent", "normal_integral", "normal_integral_angle_sum"};
    e.get = [](const RunParameters& p) -> ParameterValue { return curvature_name(p.scheme.curvature); };
    e.set = [](RunParameters& p, const ParameterValue& v) {
      p.scheme.curvature = curvature_options(std::get<std::string>(v));
    };
    e.meshlab = {.name = "Curvature", .label = "Mean curvature H",
                 .help = "How H is computed: cotangent takes H = ½ N·ΔX (default: it converges to the exact flow on "
                         "any smooth surface); normal_integral is the paper's eq. (9), the integral of normal "
                         "curvatures divided by 2π, which does not converge off spheres; normal_integral_angle_sum "
                         "divides by the vertex's angle sum instead. The result's quality holds this H."};
  }
  {
    auto& e = add(entry("mass", "--mass", ParameterType::choice,
                        "Vertex areas M of Δ = M⁻¹L: `voronoi` (eq. 10, mixed Voronoi) or `volume_gradient` (the "
                        "volume a vertex sweeps, first-order volume conservation)"));
    e.choices = {"voronoi", "volume_gradient"};
    e.get = [](const RunParameters& p) -> ParameterValue { return mass_name(p.scheme.mass); };
    e.set = [](RunParameters& p, const ParameterValue& v) { p.scheme.mass = vertex_mass(std::get<std::string>(v)); };
    e.meshlab = {.name = "Mass", .label = "Vertex areas",
                 .help = "The vertex areas M of the Laplacian Δ = M⁻¹L: voronoi is eq. (10)'s mixed Voronoi areas "
                         "(the paper's, default); volume_gradient is the volume a vertex sweeps per unit normal "
                         "motion, which conserves volume to first order in τ."};
  }
  {
    auto& e = add(entry("extrapolate", "--extrapolate", ParameterType::boolean,
                        "Richardson-extrapolate each step from one step of τ and two of τ/2: second order in τ, "
                        "three solves a step"));
    e.meshlab = {.name = "Extrapolate", .label = "Extrapolated steps",
                 .help = "Richardson-extrapolate each step from one full and two half steps: second order in τ "
                         "instead of first, at three solves a step. Off: the paper's scheme."};
    bind<bool>(e, &RunParameters::scheme, &SchemeOptions::extrapolate);
  }
  {
    auto& e = add(entry("solver", "--solver", ParameterType::choice,
                        "Linear solver: `cholmod` (supernodal Cholesky of the SPD form) or `qr` (the paper's sparse "
                        "QR, slow)"));
    e.choices = {"cholmod", "qr"};
    e.get = [](const RunParameters& p) -> ParameterValue {
      return std::string(p.solver.kind == SolverKind::qr ? "qr" : "cholmod");
    };
    e.set = [](RunParameters& p, const ParameterValue& v) {
      const std::string& s = std::get<std::string>(v);
      if (s != "cholmod" && s != "qr")
        throw InvalidParameter(fmt::format("solver must be \"cholmod\" or \"qr\", got \"{}\"", s));
      p.solver.kind = s == "qr" ? SolverKind::qr : SolverKind::cholmod;
    };
  }
  {
    auto& e = add(entry("factorisation", "--factorisation", ParameterType::choice,
                        "`reuse` a factorisation as a CG preconditioner until refactorising pays, or factorise "
                        "`every_step`"));
    e.choices = {"reuse", "every_step"};
    e.get = [](const RunParameters& p) -> ParameterValue {
      return std::string(p.solver.policy == FactorisationPolicy::reuse ? "reuse" : "every_step");
    };
    e.set = [](RunParameters& p, const ParameterValue& v) {
      const std::string& s = std::get<std::string>(v);
      if (s != "reuse" && s != "every_step")
        throw InvalidParameter(fmt::format("factorisation must be \"reuse\" or \"every_step\", got \"{}\"", s));
      p.solver.policy = s == "reuse" ? FactorisationPolicy::reuse : FactorisationPolicy::every_step;
    };
  }
  {
    auto& e = add(entry("cg_tolerance", "--cg-tolerance", ParameterType::real,
                        "Relative residual at which CG with a reused factor stops"));
    e.range = above(0);
    bind<double>(e, &RunParameters::solver, &SolverOptions::cg_tolerance);
    e.in_use = [](const RunParameters& p) { return p.solver.policy == FactorisationPolicy::reuse; };
  }

  // --- Output ---
  {
    auto& e = add(entry("snapshot_every", "--snapshot-every", ParameterType::integer,
                        "A snapshot every K steps (0: of the first and last surface only)"));
    e.range = at_least(0);
    e.resumable = true;
    bind<long>(e, &RunParameters::snapshot_every);
  }
  {
    auto& e = add(entry("checkpoint_every", "--checkpoint-every", ParameterType::integer,
                        "A checkpoint every K steps"));
    e.range = at_least(1);
    e.resumable = true;
    bind<long>(e, &RunParameters::checkpoint_every);
  }

  // --- Flow options ---
  {
    auto& e = add(entry("conserve_volume", "--conserve-volume", ParameterType::boolean,
                        "Restore each component's material volume after every step (a uniform normal offset)"));
    e.meshlab = {.name = "ConserveVolume", .label = "Conserve volume exactly",
                 .help = "After each step, move every component along its normals by one uniform distance "
                         "that restores its volume (an open surface's boundary stays put; its volume is that "
                         "closed by flat caps over its boundary). The flow conserves volume in theory; this removes the "
                         "small drift of the discrete scheme."};
    bind<bool>(e, &RunParameters::conserve_volume);
  }
  {
    auto& e = add(entry("refinement", "--refinement", ParameterType::real,
                        "s, the refinement of the curvature-adapted sizing and the time-step bound: edges per "
                        "radius × √s, displacement bound ÷ s, so event times converge as ℓ shrinks (0: automatic, "
                        "max(1, R / (8 ℓ)) for the initial surface's typical radius of curvature R, written to "
                        "run.toml as a number; 1: the sizing and bound as given)"));
    e.range = {.min = 0, .max = 1e6};
    bind<double>(e, &RunParameters::refinement);
  }
  {
    auto& e = add(entry("look_ahead", "--look-ahead", ParameterType::boolean,
                        "Take the next step's first trial on the second core while the surface is looked at for "
                        "re-triangulation (the same results either way; off: one after the other)"));
    e.resumable = true;
    bind<bool>(e, &RunParameters::look_ahead);
  }
  {
    auto& e = add(entry("boundary", "--boundary", ParameterType::choice,
                        "At the boundary of an open surface: `fixed` (the rim stays put and no material crosses "
                        "it; the default) or `paper` (the rim moves, with H = 0 there: the paper's §4.3)"));
    e.choices = {"fixed", "paper"};
    e.key_aliases = {"fixed_boundary"}; // its older boolean key: true is `fixed`, false `paper`
    e.shorthands = {{"--fixed-boundary", "fixed", "A fixed boundary (the default): --boundary fixed"}};
    e.get = [](const RunParameters& p) -> ParameterValue {
      return std::string(boundary_condition_name(p.scheme.boundary));
    };
    e.set = [](RunParameters& p, const ParameterValue& v) {
      p.scheme.boundary = boundary_condition(std::get<std::string>(v));
    };
    e.meshlab = {.name = "FixedBoundary", .label = "Fixed boundary",
                 .help = "At the boundary of an open surface. On: the boundary stays where it is and no material "
                         "flows through it (the surface ends on a large body that does not move), so the volume "
                         "under the surface is conserved. Off: boundary vertices move like interior ones, with zero "
                         "mean curvature there (the paper's rule; the volume is not conserved).",
                 .boolean_choices = std::pair<std::string, std::string>{"paper", "fixed"}};
  }

  // --- [adaptive]: the adaptive time step (flow/time_step.h) ---
  const auto adaptive = [&](const char* key, const char* flag, ParameterType type, ParameterRange range,
                            const char* help) -> ParameterEntry& {
    auto& e = add(entry(key, flag, type, help));
    e.range = range;
    e.in_use = adaptive_steps;
    return e;
  };
  bind<double>(adaptive("adaptive.initial_tau", "--initial-tau", ParameterType::real, at_least(0),
                        "Adaptive τ: the first step's τ (0: automatic, from ΔH and the edge lengths)"),
               &RunParameters::time_step, &TimeStepOptions::adaptive, &AdaptiveOptions::initial_tau);
  bind<double>(adaptive("adaptive.max_displacement", "--max-displacement", ParameterType::real, {.min = 0, .min_open = true, .infinite_allowed = true},
                        "Adaptive τ: bound on a step's normal displacement, relative to the local edge length"),
               &RunParameters::time_step, &TimeStepOptions::adaptive, &AdaptiveOptions::max_displacement);
  bind<double>(adaptive("adaptive.growth", "--tau-growth", ParameterType::real,
                        {.min = 1, .infinite_allowed = true},
                        "Adaptive τ: largest growth factor of τ per accepted step"),
               &RunParameters::time_step, &TimeStepOptions::adaptive, &AdaptiveOptions::growth);
  bind<double>(adaptive("adaptive.shrink", "--tau-shrink", ParameterType::real,
                        {.min = 0, .max = 1, .min_open = true, .max_open = true},
                        "Adaptive τ: factor applied to τ on a rejected step"),
               &RunParameters::time_step, &TimeStepOptions::adaptive, &AdaptiveOptions::shrink);
  bind<double>(adaptive("adaptive.safety", "--tau-safety", ParameterType::real, {.min = 0, .max = 1, .min_open = true},
                        "Adaptive τ: aim this fraction of the bounds when predicting the next τ"),
               &RunParameters::time_step, &TimeStepOptions::adaptive, &AdaptiveOptions::safety);
  bind<double>(adaptive("adaptive.max_volume_change", "--max-volume-change", ParameterType::real, {.min = 0, .min_open = true, .infinite_allowed = true},
                        "Adaptive τ: bound on a component's relative change of material volume per step"),
               &RunParameters::time_step, &TimeStepOptions::adaptive, &AdaptiveOptions::max_volume_change);
  bind<double>(adaptive("adaptive.min_tau", "--min-tau", ParameterType::real, above(0),
                        "Adaptive τ: below this τ the run is declared unstable"),
               &RunParameters::time_step, &TimeStepOptions::adaptive, &AdaptiveOptions::min_tau);
  bind<double>(adaptive("adaptive.max_tau", "--max-tau", ParameterType::real,
                        {.min = 0, .min_open = true, .infinite_allowed = true},
                        "Adaptive τ: the largest τ (inf: none)"),
               &RunParameters::time_step, &TimeStepOptions::adaptive, &AdaptiveOptions::max_tau);
  bind<long>(adaptive("adaptive.max_rejections", "--max-rejections", ParameterType::integer, at_least(1),
                      "Adaptive τ: rejected trials in a row before the run is declared unstable"),
             &RunParameters::time_step, &TimeStepOptions::adaptive, &AdaptiveOptions::max_rejections);
  bind<long>(adaptive("adaptive.start_steps", "--start-steps", ParameterType::integer, at_least(0),
                      "Adaptive τ: a run's first steps that may be start steps, whose τ_s = start_damping·(ℓ/π)⁴ "
                      "damps what the mesh does not resolve (noise, sharp edges, creases) when that, not the "
                      "resolved scales, would set τ (0: none)"),
             &RunParameters::time_step, &TimeStepOptions::adaptive, &AdaptiveOptions::start_steps);
  bind<double>(adaptive("adaptive.start_damping", "--start-damping", ParameterType::real, above(0),
                        "Adaptive τ: a start step's τ_s·(π/ℓ)⁴, the damping of the wavelength 2ℓ per start step"),
               &RunParameters::time_step, &TimeStepOptions::adaptive, &AdaptiveOptions::start_damping);
  {
    auto& e = adaptive("adaptive.tolerance", "--tolerance", ParameterType::real, at_least(0),
                       "Adaptive τ: bound on the extrapolated step's local error estimate, relative to the local "
                       "edge length (0: off); needs extrapolated steps, which the flag implies");
    e.in_use = nullptr; // checked in every mode, like its need for extrapolated steps
    e.implies = {{"extrapolate", true, true}};
    bind<double>(e, &RunParameters::time_step, &TimeStepOptions::adaptive, &AdaptiveOptions::tolerance);
  }

  // --- [retriangulation]: when (flow/retriangulation.h) and how (retri/pipeline.h) ---
  using RS = RetriangulationSchedule;
  using RO = RetriangulationOptions;
  {
    auto& e = add(entry("retriangulation.enabled", "--retriangulate", ParameterType::boolean,
                        "Re-triangulate between steps when the surface intersects itself or its triangles degrade "
                        "(paper §3.2.1); off, a step that makes the surface intersect itself stops the run (exit 3)"));
    e.meshlab = {.name = "Retriangulate", .label = "Re-triangulate",
                 .help = "Re-triangulate between steps when the surface intersects itself (a pinch-off, a hole "
                         "closing, bodies touching) or its triangles degrade (an angle below 15°, an edge outside "
                         "[ℓ/2, 2ℓ]), by the pipeline of <i>Surface diffusion: re-triangulate</i>. The number of "
                         "vertices then changes. On by default, as in sdflow run; off, the filter fails at the first "
                         "step that makes the surface intersect itself."};
    bind<bool>(e, &RunParameters::retriangulation, &RS::enabled);
  }
  {
    auto& e = add(entry("retriangulation.every", "--retriangulate-every", ParameterType::integer,
                        "Look at the surface after every k-th step"));
    e.range = at_least(1);
    bind<long>(e, &RunParameters::retriangulation, &RS::every);
  }
  {
    auto& e = add(entry("retriangulation.min_angle", "--min-angle", ParameterType::real,
                        "Degraded: a triangle with an angle below this (degrees)"));
    e.range = {.min = 0, .max = 60, .max_open = true};
    bind<double>(e, &RunParameters::retriangulation, &RS::min_angle_deg);
  }
  {
    auto& e = add(entry("retriangulation.edge_ratio", "--edge-ratio", ParameterType::real,
                        "Degraded: an edge longer than r·ℓ_v or shorter than ℓ_v/r of its local target ℓ_v"));
    e.range = above(1);
    bind<double>(e, &RunParameters::retriangulation, &RS::edge_ratio);
  }
  {
    auto& e = add(entry("retriangulation.degraded_fraction", "--degraded-fraction", ParameterType::real,
                        "Re-triangulate when more than this fraction of the triangles is degraded (0: any one)"));
    e.range = {.min = 0, .max = 1, .max_open = true};
    bind<double>(e, &RunParameters::retriangulation, &RS::degraded_fraction);
  }
  {
    auto& e = add(entry("retriangulation.always", "--retriangulate-always", ParameterType::boolean,
                        "Run the whole pipeline after every k-th step, needed or not (the paper's practice)"));
    bind<bool>(e, &RunParameters::retriangulation, &RS::always);
  }
  {
    auto& e = add(entry("retriangulation.local", "--retriangulate-local", ParameterType::boolean,
                        "When only degraded elements call for a re-triangulation, remesh just the region around them "
                        "(three rings of faces, boundary kept) instead of running the whole pipeline (the whole "
                        "pipeline when that fails or the region holds more than a tenth of the surface)"));
    bind<bool>(e, &RunParameters::retriangulation, &RS::local);
  }
  {
    auto& e = add(entry("retriangulation.local_surgery", "--local-surgery", ParameterType::boolean,
                        "At a self-intersection, rebuild only the faces near the crossing (the whole pipeline when "
                        "that fails, and for components touching each other)"));
    bind<bool>(e, &RunParameters::retriangulation, &RS::local_surgery);
  }
  {
    auto& e = add(entry("retriangulation.edge_length", "--edge-length", ParameterType::real,
                        "ℓ, the target edge length (0: the initial surface's mean edge length, written to run.toml "
                        "as a number)"));
    e.range = at_least(0);
    e.meshlab = {.name = "EdgeLength", .label = "Re-triangulation edge length ℓ",
                 .help = "Target edge length of the re-triangulation, used only when it is on (≥ 0; 0: the mesh's "
                         "mean edge length at the start). The default is this mesh's mean edge length.",
                 .source = MeshlabParameter::Default::mean_edge_length};
    bind<double>(e, &RunParameters::retriangulation, &RS::pipeline, &RO::edge_length);
  }
  {
    auto& e = add(entry("retriangulation.remesh_iterations", "--remesh-iterations", ParameterType::integer,
                        "Rounds of isotropic remeshing (0: none)"));
    e.range = at_least(0);
    bind<long>(e, &RunParameters::retriangulation, &RS::pipeline, &RO::remesh_iterations);
  }
  {
    auto& e = add(entry("retriangulation.edges_per_radius", "--edges-per-radius", ParameterType::real,
                        "Curvature-adapted ℓ: edges per radius of curvature where finer than ℓ (0: uniform ℓ, the "
                        "paper's)"));
    e.range = at_least(0);
    bind<double>(e, &RunParameters::retriangulation, &RS::pipeline, &RO::edges_per_radius);
  }
  {
    auto& e = add(entry("retriangulation.min_edge_fraction", "--min-edge-fraction", ParameterType::real,
                        "Floor of the adapted ℓ, as a fraction of ℓ"));
    e.range = {.min = 0, .max = 1, .min_open = true};
    bind<double>(e, &RunParameters::retriangulation, &RS::pipeline, &RO::min_edge_fraction);
  }
  {
    auto& e = add(entry("retriangulation.restore_volume", "--restore-volume", ParameterType::boolean,
                        "Give each component (or group that split or fused) back the material volume a "
                        "re-triangulation took or added"));
    bind<bool>(e, &RunParameters::retriangulation, &RS::restore_volume);
  }
  {
    auto& e = add(entry("retriangulation.curved_projection", "--curved-projection", ParameterType::boolean,
                        "Remesh onto the smooth surface the triangles sample, not onto the flat triangles"));
    bind<bool>(e, &RunParameters::retriangulation, &RS::pipeline, &RO::curved_projection);
  }
  {
    auto& e = add(entry("retriangulation.neighbours", "--neighbours", ParameterType::integer,
                        "k, the nearest neighbours of the jet-fitted point normals"));
    e.range = at_least(6);
    bind<long>(e, &RunParameters::retriangulation, &RS::pipeline, &RO::normals, &PointNormalsOptions::neighbours);
  }
  {
    auto& e = add(entry("retriangulation.fill_holes", "--fill-holes", ParameterType::boolean,
                        "Fill the holes a rebuild from points leaves"));
    bind<bool>(e, &RunParameters::retriangulation, &RS::pipeline, &RO::fill_holes);
  }
  {
    auto& e = add(entry("retriangulation.max_hole_length", "--max-hole-length", ParameterType::real,
                        "Holes with a longer boundary stay open (0: automatic)"));
    e.range = at_least(0);
    e.range.infinite_allowed = true; // as validate_retriangulation_options allows
    bind<double>(e, &RunParameters::retriangulation, &RS::pipeline, &RO::max_hole_length);
  }
  {
    auto& e = add(entry("retriangulation.min_component_faces", "--min-component-faces", ParameterType::integer,
                        "Components with fewer triangles are dropped as debris"));
    e.range = at_least(1);
    bind<long>(e, &RunParameters::retriangulation, &RS::pipeline, &RO::min_component_faces);
  }
  {
    auto& e = add(entry("retriangulation.min_component_thickness", "--min-component-thickness", ParameterType::real,
                        "Closed components whose volume is below this fraction of ℓ times their area are dropped"));
    e.range = at_least(0);
    bind<double>(e, &RunParameters::retriangulation, &RS::pipeline, &RO::min_component_thickness);
  }

  // --- [reference_sphere]: the d1/d2 columns of metrics.csv ---
  {
    auto& e = add(entry("reference_sphere.centre", "--reference-centre", ParameterType::point,
                        "Centre of the sphere the d1/d2 columns of metrics.csv measure against"));
    bind<Eigen::Vector3d>(e, &RunParameters::reference_centre);
  }
  {
    auto& e = add(entry("reference_sphere.radius", "--reference-radius", ParameterType::real,
                        "Radius of that sphere"));
    e.range = above(0);
    bind<double>(e, &RunParameters::reference_radius);
  }
  return s;
}

std::string quoted(const std::string& s)
{
  std::ostringstream out;
  out << toml::value<std::string>(s);
  return out.str();
}

//! Levenshtein distance, for suggestions.
std::size_t edit_distance(const std::string& a, const std::string& b)
{
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
    row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

} // namespace

std::string type_name(ParameterType type)
{
  switch (type) {
  case ParameterType::integer: return "integer";
  case ParameterType::real: return "real";
  case ParameterType::boolean: return "boolean";
  case ParameterType::choice: return "choice";
  case ParameterType::path: return "path";
  case ParameterType::point: return "point";
  case ParameterType::schedule: return "schedule";
  }
  return "?";
}

bool ParameterRange::contains(double v) const
{
  if (std::isnan(v) || (std::isinf(v) && !infinite_allowed))
    return false;
  const bool above_min = min_open ? v > min : v >= min;
  const bool below_max = max_open ? v < max : v <= max;
  return above_min && below_max;
}

std::string ParameterRange::text() const
{
  const bool has_min = std::isfinite(min), has_max = std::isfinite(max);
  if (has_min && has_max)
    return fmt::format("in {}{}, {}{}", min_open ? '(' : '[', number_text(min), number_text(max), max_open ? ')' : ']');
  if (has_min)
    return fmt::format("{} {}", min_open ? ">" : "≥", number_text(min));
  if (has_max)
    return fmt::format("{} {}", max_open ? "<" : "≤", number_text(max));
  return "";
}

bool ScheduleSetting::operator==(const ScheduleSetting& other) const
{
  return file == other.file &&
         std::equal(entries.begin(), entries.end(), other.entries.begin(), other.entries.end(),
                    [](const ScheduleEntry& a, const ScheduleEntry& b) {
                      return a.first_step == b.first_step && a.last_step == b.last_step && a.tau == b.tau;
                    });
}

std::string ParameterEntry::section() const
{
  const auto dot = key.find('.');
  return dot == std::string::npos ? std::string() : key.substr(0, dot);
}

std::string ParameterEntry::name() const
{
  const auto dot = key.find('.');
  return dot == std::string::npos ? key : key.substr(dot + 1);
}

std::string ParameterEntry::default_text() const
{
  // None: no path, no schedule, no preset, no end time, no constant τ (0 is outside its range).
  if (type == ParameterType::path || type == ParameterType::schedule)
    return "none";
  const RunParameters defaults;
  const ParameterValue value = get(defaults);
  if (const auto* text = std::get_if<std::string>(&value); text && text->empty())
    return "none";
  if (const auto* number = std::get_if<double>(&value);
      number && (!range.contains(*number) || (std::isinf(*number) && written && !written(defaults))))
    return "none";
  return toml_text(value);
}

const std::vector<ParameterEntry>& parameter_schema()
{
  static const std::vector<ParameterEntry> schema = build_schema();
  return schema;
}

const ParameterEntry* find_parameter(const std::string& key)
{
  for (const ParameterEntry& e : parameter_schema())
    if (e.key == key || std::find(e.key_aliases.begin(), e.key_aliases.end(), key) != e.key_aliases.end())
      return &e;
  return nullptr;
}

const ParameterEntry* find_meshlab_parameter(const std::string& name)
{
  for (const ParameterEntry& e : parameter_schema())
    if (!e.meshlab.name.empty() && e.meshlab.name == name)
      return &e;
  return nullptr;
}

std::string closest_parameter_key(const std::string& key)
{
  std::string best;
  std::size_t best_distance = 0;
  for (const ParameterEntry& e : parameter_schema()) {
    std::vector<std::string> names = {e.key};
    names.insert(names.end(), e.key_aliases.begin(), e.key_aliases.end());
    for (const std::string& name : names) {
      // Within a table, compare the names after the section; a key in the wrong table is close too.
      const std::size_t d = std::min(edit_distance(key, name), edit_distance(key, e.name()));
      if (best.empty() || d < best_distance) {
        best = e.key;
        best_distance = d;
      }
    }
  }
  const std::size_t bound = std::max<std::size_t>(2, key.size() / 3);
  return best_distance <= bound ? best : std::string();
}

std::string toml_text(const ParameterValue& value)
{
  return std::visit(
      [](const auto& v) -> std::string {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, long>) {
          return fmt::format("{}", v);
        } else if constexpr (std::is_same_v<T, double>) {
          if (std::isnan(v))
            return "nan";
          if (std::isinf(v))
            return v > 0 ? "inf" : "-inf";
          return fmt::format("{}", v);
        } else if constexpr (std::is_same_v<T, bool>) {
          return v ? "true" : "false";
        } else if constexpr (std::is_same_v<T, std::string>) {
          return fmt::format("\"{}\"", v); // a choice's name: letters and underscores
        } else if constexpr (std::is_same_v<T, std::filesystem::path>) {
          return quoted(std::filesystem::absolute(v).lexically_normal().string());
        } else if constexpr (std::is_same_v<T, Eigen::Vector3d>) {
          return fmt::format("[{}, {}, {}]", v.x(), v.y(), v.z());
        } else {
          std::string s = "[";
          for (const ScheduleEntry& e : v.entries)
            s += fmt::format("[{}, {}, {}], ", e.first_step, e.last_step, e.tau);
          return s + "]";
        }
      },
      value);
}

void check_range(const ParameterEntry& entry, const ParameterValue& value)
{
  double number = 0;
  if (const long* i = std::get_if<long>(&value))
    number = static_cast<double>(*i);
  else if (const double* d = std::get_if<double>(&value))
    number = *d;
  else
    return;
  if (!entry.range.contains(number))
    throw InvalidParameter(fmt::format("{} must be {}{}, got {}", entry.key, std::isinf(number) ? "finite and " : "",
                                       entry.range.text(), toml_text(value)));
}

std::string parameter_table_markdown()
{
  std::string s = "| key | flag | type | default | range | `--resume` | meaning |\n|---|---|---|---|---|---|---|\n";
  for (const ParameterEntry& e : parameter_schema()) {
    std::string key = "`" + e.key + "`";
    for (const std::string& alias : e.key_aliases)
      key += " (or `" + alias + "`)";
    std::string flag = "`" + e.flag + "`";
    if (!e.flag_aliases.empty())
      flag += " (or `" + fmt::format("{}", fmt::join(e.flag_aliases, "`, `")) + "`)";
    for (const auto& shorthand : e.shorthands)
      flag += ", `" + shorthand.flag + "`";
    if (e.type == ParameterType::boolean)
      flag += ", `--no-" + e.flag.substr(2) + "`";
    std::string type = type_name(e.type);
    if (e.type == ParameterType::choice) {
      type.clear();
      for (const std::string& c : e.choices)
        type += (type.empty() ? "" : " \\| ") + ("`" + c + "`");
    }
    const std::string default_text = e.default_text();
    std::string meaning = e.help;
    if (!e.meshlab.name.empty())
      meaning += " (MeshLab: `" + e.meshlab.name + "`)";
    // A '|' inside a cell would end it.
    std::string cell;
    for (char c : meaning)
      cell += c == '|' ? std::string("\\|") : std::string(1, c);
    s += fmt::format("| {} | {} | {} | {} | {} | {} | {} |\n", key, flag, type,
                     default_text == "none" ? "—" : "`" + default_text + "`", e.range.text(),
                     e.resumable ? "yes" : "", cell);
  }
  return s;
}

std::string meshlab_parameter_table_markdown()
{
  std::string s = "| parameter (.mlx name) | meaning | `sdflow run` |\n|---|---|---|\n";
  for (const ParameterEntry& e : parameter_schema()) {
    if (e.meshlab.name.empty())
      continue;
    std::string cell;
    for (char c : e.meshlab.help.empty() ? e.help : e.meshlab.help)
      cell += c == '|' ? std::string("\\|") : std::string(1, c);
    std::string flag = "`" + e.flag + "`";
    for (const auto& shorthand : e.shorthands)
      flag += ", `" + shorthand.flag + "`";
    if (e.type == ParameterType::boolean)
      flag += ", `--no-" + e.flag.substr(2) + "`";
    s += fmt::format("| {} (`{}`) | {} | {} |\n", e.meshlab.label, e.meshlab.name, cell, flag);
  }
  return s;
}

} // namespace sdflow
