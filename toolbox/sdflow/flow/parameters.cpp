#include "sdflow/flow/parameters.h"

#include "sdflow/errors.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <cmath>
#include <set>
#include <sstream>

namespace sdflow {
namespace {

[[noreturn]] void bad(const std::filesystem::path& file, const toml::node& node, const std::string& what)
{
  throw InvalidParameter(fmt::format("{}:{}: {}", file.string(), node.source().begin.line, what));
}

template <typename T>
T get(const std::filesystem::path& file, const toml::node& node, const char* key)
{
  if constexpr (std::is_same_v<T, double>) {
    if (auto v = node.value<double>()) // integers are accepted for real values
      return *v;
  } else if constexpr (std::is_same_v<T, long>) {
    if (node.is_integer())
      return static_cast<long>(*node.value<int64_t>());
  } else if constexpr (std::is_same_v<T, bool>) {
    if (node.is_boolean())
      return *node.value<bool>();
  } else {
    if (node.is_string())
      return *node.value<std::string>();
  }
  bad(file, node, fmt::format("`{}` has the wrong type", key));
}

std::filesystem::path resolve(const std::filesystem::path& file, const std::string& path)
{
  const std::filesystem::path p(path);
  return p.is_absolute() ? p : (file.parent_path() / p).lexically_normal();
}

void check_keys(const std::filesystem::path& file, const toml::table& table, const std::set<std::string>& known,
                const std::string& where)
{
  for (const auto& [key, node] : table)
    if (!known.count(std::string(key.str())))
      bad(file, node, fmt::format("unknown key `{}{}`", where, key.str()));
}

TauSchedule inline_schedule(const std::filesystem::path& file, const toml::array& rows)
{
  std::vector<ScheduleEntry> entries;
  for (const auto& row : rows) {
    const toml::array* r = row.as_array();
    if (!r || r->size() != 3 || !r->get(0)->is_integer() || !r->get(1)->is_integer() || !r->get(2)->value<double>())
      bad(file, row, "a schedule entry must be [first_step, last_step, tau]");
    entries.push_back({static_cast<long>(*r->get(0)->value<int64_t>()), static_cast<long>(*r->get(1)->value<int64_t>()),
                       *r->get(2)->value<double>()});
  }
  return TauSchedule(std::move(entries));
}

std::string quoted(const std::string& s)
{
  std::ostringstream out;
  out << toml::value<std::string>(s);
  return out.str();
}

} // namespace

std::string curvature_name(const CurvatureOptions& options)
{
  if (options.method == CurvatureMethod::cotangent)
    return "cotangent";
  return options.normalisation == AngleNormalisation::angle_sum ? "normal_integral_angle_sum" : "normal_integral";
}

CurvatureOptions curvature_options(const std::string& name)
{
  if (name == "normal_integral")
    return {};
  if (name == "normal_integral_angle_sum")
    return {.normalisation = AngleNormalisation::angle_sum};
  if (name == "cotangent")
    return {.method = CurvatureMethod::cotangent};
  throw InvalidParameter(fmt::format("curvature must be \"normal_integral\", \"normal_integral_angle_sum\" or "
                                     "\"cotangent\", got \"{}\"", name));
}

std::string mass_name(VertexMass mass)
{
  return mass == VertexMass::volume_gradient ? "volume_gradient" : "voronoi";
}

VertexMass vertex_mass(const std::string& name)
{
  if (name == "voronoi")
    return VertexMass::voronoi;
  if (name == "volume_gradient")
    return VertexMass::volume_gradient;
  throw InvalidParameter(fmt::format("mass must be \"voronoi\" or \"volume_gradient\", got \"{}\"", name));
}

void apply_preset(const std::string& name, RunParameters& p)
{
  RunParameters defaults;
  const RunParameters* source = &defaults;
  RunParameters paper;
  if (name == "paper") {
    paper.scheme.curvature = {.method = CurvatureMethod::normal_curvature_integral};
    paper.scheme.mass = VertexMass::voronoi;
    paper.scheme.extrapolate = false;
    paper.time_step.adaptive.tolerance = 0;
    paper.retriangulation.pipeline.edges_per_radius = 0;
    paper.retriangulation.pipeline.curved_projection = false;
    paper.retriangulation.restore_volume = false;
    source = &paper;
  } else if (name != "default") {
    throw InvalidParameter(fmt::format("preset must be \"paper\" or \"default\", got \"{}\"", name));
  }
  p.scheme.curvature = source->scheme.curvature;
  p.scheme.mass = source->scheme.mass;
  p.scheme.extrapolate = source->scheme.extrapolate;
  p.time_step.adaptive.tolerance = source->time_step.adaptive.tolerance;
  p.retriangulation.pipeline.edges_per_radius = source->retriangulation.pipeline.edges_per_radius;
  p.retriangulation.pipeline.min_edge_fraction = source->retriangulation.pipeline.min_edge_fraction;
  p.retriangulation.pipeline.curved_projection = source->retriangulation.pipeline.curved_projection;
  p.retriangulation.restore_volume = source->retriangulation.restore_volume;
}

void read_run_parameters(const std::filesystem::path& file, RunParameters& p)
{
  toml::table table;
  try {
    table = toml::parse_file(file.string());
  } catch (const toml::parse_error& e) {
    throw IoError(fmt::format("{}:{}: {}", file.string(), e.source().begin.line, e.description()));
  }
  check_keys(file, table,
             {"preset", "input", "out", "steps", "stop_at_topology_change", "t_end", "time_step", "tau", "schedule", "schedule_retries", "beta", "curvature",
              "mass", "extrapolate", "solver", "factorisation", "cg_tolerance", "snapshot_every", "checkpoint_every",
              "conserve_volume", "fixed_boundary", "adaptive", "retriangulation", "reference_sphere"},
             "");
  if (const toml::node* preset = table.get("preset")) {
    try {
      apply_preset(get<std::string>(file, *preset, "preset"), p);
    } catch (const InvalidParameter& e) {
      bad(file, *preset, e.what());
    }
  }
  std::optional<std::string> mode;
  for (const auto& [key_view, node] : table) {
    const std::string key(key_view.str());
    if (key == "preset") continue;
    else if (key == "input") p.input = resolve(file, get<std::string>(file, node, "input"));
    else if (key == "out") p.output_dir = resolve(file, get<std::string>(file, node, "out"));
    else if (key == "steps") p.steps = get<long>(file, node, "steps");
    else if (key == "t_end") p.end_time = get<double>(file, node, "t_end");
    else if (key == "stop_at_topology_change")
      p.stop_at_topology_change = get<bool>(file, node, "stop_at_topology_change");
    else if (key == "time_step") mode = get<std::string>(file, node, "time_step");
    else if (key == "tau") {
      p.time_step.tau = get<double>(file, node, "tau");
      p.time_step.mode = TimeStepMode::constant;
    } else if (key == "schedule_retries") {
      p.time_step.schedule_retries = static_cast<int>(get<long>(file, node, "schedule_retries"));
    } else if (key == "schedule") {
      if (const toml::array* rows = node.as_array()) {
        p.time_step.schedule = inline_schedule(file, *rows);
        p.time_step.schedule_file.clear();
      } else {
        p.time_step.schedule_file = resolve(file, get<std::string>(file, node, "schedule"));
        p.time_step.schedule = read_schedule(p.time_step.schedule_file);
      }
      p.time_step.mode = TimeStepMode::schedule;
    } else if (key == "beta") p.scheme.beta = get<double>(file, node, "beta");
    else if (key == "curvature") {
      try {
        p.scheme.curvature = curvature_options(get<std::string>(file, node, "curvature"));
      } catch (const InvalidParameter& e) {
        bad(file, node, e.what());
      }
    }
    else if (key == "extrapolate") p.scheme.extrapolate = get<bool>(file, node, "extrapolate");
    else if (key == "mass") {
      try {
        p.scheme.mass = vertex_mass(get<std::string>(file, node, "mass"));
      } catch (const InvalidParameter& e) {
        bad(file, node, e.what());
      }
    }
    else if (key == "solver") {
      const std::string s = get<std::string>(file, node, "solver");
      if (s != "cholmod" && s != "qr")
        bad(file, node, fmt::format("solver must be \"cholmod\" or \"qr\", got \"{}\"", s));
      p.solver.kind = s == "qr" ? SolverKind::qr : SolverKind::cholmod;
    } else if (key == "factorisation") {
      const std::string s = get<std::string>(file, node, "factorisation");
      if (s != "reuse" && s != "every_step")
        bad(file, node, fmt::format("factorisation must be \"reuse\" or \"every_step\", got \"{}\"", s));
      p.solver.policy = s == "reuse" ? FactorisationPolicy::reuse : FactorisationPolicy::every_step;
    } else if (key == "cg_tolerance") p.solver.cg_tolerance = get<double>(file, node, "cg_tolerance");
    else if (key == "snapshot_every") p.snapshot_every = get<long>(file, node, "snapshot_every");
    else if (key == "checkpoint_every") p.checkpoint_every = get<long>(file, node, "checkpoint_every");
    else if (key == "conserve_volume") p.conserve_volume = get<bool>(file, node, "conserve_volume");
    else if (key == "fixed_boundary")
      p.scheme.boundary = get<bool>(file, node, "fixed_boundary") ? BoundaryMotion::fixed : BoundaryMotion::paper;
    else if (key == "adaptive") {
      const toml::table* t = node.as_table();
      if (!t)
        bad(file, node, "`adaptive` must be a table of the adaptive rule's parameters");
      check_keys(file, *t, {"initial_tau", "max_displacement", "growth", "shrink", "safety", "max_volume_change",
                            "min_tau", "max_tau", "max_rejections", "tolerance"}, "adaptive.");
      AdaptiveOptions& a = p.time_step.adaptive;
      for (const auto& [k, n] : *t) {
        const std::string name(k.str());
        if (name == "max_rejections") a.max_rejections = static_cast<int>(get<long>(file, n, "max_rejections"));
        else {
          const double v = get<double>(file, n, name.c_str());
          if (name == "initial_tau") a.initial_tau = v;
          else if (name == "max_displacement") a.max_displacement = v;
          else if (name == "growth") a.growth = v;
          else if (name == "shrink") a.shrink = v;
          else if (name == "safety") a.safety = v;
          else if (name == "max_volume_change") a.max_volume_change = v;
          else if (name == "min_tau") a.min_tau = v;
          else if (name == "tolerance") a.tolerance = v;
          else a.max_tau = v;
        }
      }
    } else if (key == "retriangulation") {
      const toml::table* t = node.as_table();
      if (!t)
        bad(file, node, "`retriangulation` must be a table of the re-triangulation parameters");
      check_keys(file, *t, {"enabled", "every", "min_angle", "edge_ratio", "degraded_fraction", "always", "edge_length",
                            "remesh_iterations", "neighbours", "fill_holes", "max_hole_length", "min_component_faces",
                            "min_component_thickness", "edges_per_radius", "min_edge_fraction", "restore_volume",
                            "curved_projection"},
                 "retriangulation.");
      RetriangulationSchedule& r = p.retriangulation;
      for (const auto& [k, n] : *t) {
        const std::string name(k.str());
        if (name == "enabled") r.enabled = get<bool>(file, n, "enabled");
        else if (name == "always") r.always = get<bool>(file, n, "always");
        else if (name == "fill_holes") r.pipeline.fill_holes = get<bool>(file, n, "fill_holes");
        else if (name == "restore_volume") r.restore_volume = get<bool>(file, n, "restore_volume");
        else if (name == "curved_projection")
          r.pipeline.curved_projection = get<bool>(file, n, "curved_projection");
        else if (name == "edges_per_radius") r.pipeline.edges_per_radius = get<double>(file, n, "edges_per_radius");
        else if (name == "min_edge_fraction") r.pipeline.min_edge_fraction = get<double>(file, n, "min_edge_fraction");
        else if (name == "every") r.every = get<long>(file, n, "every");
        else if (name == "remesh_iterations")
          r.pipeline.remesh_iterations = static_cast<int>(get<long>(file, n, "remesh_iterations"));
        else if (name == "neighbours") r.pipeline.normals.neighbours = static_cast<int>(get<long>(file, n, "neighbours"));
        else if (name == "min_component_faces")
          r.pipeline.min_component_faces = static_cast<int>(get<long>(file, n, "min_component_faces"));
        else if (name == "min_component_thickness")
          r.pipeline.min_component_thickness = get<double>(file, n, "min_component_thickness");
        else if (name == "min_angle") r.min_angle_deg = get<double>(file, n, "min_angle");
        else if (name == "edge_ratio") r.edge_ratio = get<double>(file, n, "edge_ratio");
        else if (name == "degraded_fraction") r.degraded_fraction = get<double>(file, n, "degraded_fraction");
        else if (name == "edge_length") r.pipeline.target_edge_length = get<double>(file, n, "edge_length");
        else r.pipeline.max_hole_length = get<double>(file, n, "max_hole_length");
      }
    } else if (key == "reference_sphere") {
      const toml::table* t = node.as_table();
      if (!t)
        bad(file, node, "`reference_sphere` must be a table with `centre` and `radius`");
      check_keys(file, *t, {"centre", "radius"}, "reference_sphere.");
      if (const toml::node* r = t->get("radius"))
        p.reference_radius = get<double>(file, *r, "radius");
      if (const toml::node* c = t->get("centre")) {
        const toml::array* a = c->as_array();
        if (!a || a->size() != 3 || !a->get(0)->value<double>() || !a->get(1)->value<double>() ||
            !a->get(2)->value<double>())
          bad(file, *c, "reference_sphere.centre must be [x, y, z]");
        p.reference_centre = {*a->get(0)->value<double>(), *a->get(1)->value<double>(), *a->get(2)->value<double>()};
      }
    }
  }
  if (mode) {
    if (*mode == "constant") p.time_step.mode = TimeStepMode::constant;
    else if (*mode == "schedule") p.time_step.mode = TimeStepMode::schedule;
    else if (*mode == "adaptive") p.time_step.mode = TimeStepMode::adaptive;
    else
      bad(file, *table.get("time_step"), fmt::format("time_step must be \"constant\", \"schedule\" or \"adaptive\", "
                                                     "got \"{}\"", *mode));
  }
}

void validate_run_parameters(const RunParameters& p)
{
  if (p.steps == 0 && std::isinf(p.end_time))
    throw InvalidParameter("no stop condition: give a number of steps or an end time");
  validate_flow_parameters(p);
}

void validate_flow_parameters(const RunParameters& p)
{
  if (p.steps < 0)
    throw InvalidParameter(fmt::format("steps must be ≥ 0, got {}", p.steps));
  if (!(p.end_time > 0))
    throw InvalidParameter(fmt::format("the end time must be positive, got {}", p.end_time));
  if (!(p.scheme.beta >= 0) || !std::isfinite(p.scheme.beta))
    throw InvalidParameter(fmt::format("β must be finite and ≥ 0, got {}", p.scheme.beta));
  if (p.snapshot_every < 0 || p.checkpoint_every < 1)
    throw InvalidParameter(fmt::format("need snapshot_every ≥ 0 (got {}) and checkpoint_every ≥ 1 (got {})",
                                       p.snapshot_every, p.checkpoint_every));
  if (!(p.reference_radius > 0))
    throw InvalidParameter(fmt::format("the reference sphere's radius must be positive, got {}", p.reference_radius));
  TimeStepController check(p.time_step); // validates the time-step options
  if (p.time_step.adaptive.tolerance > 0 && !p.scheme.extrapolate)
    throw InvalidParameter(fmt::format("an error tolerance ({}) needs extrapolated steps (extrapolate = true): "
                                       "they provide the error estimate",
                                       p.time_step.adaptive.tolerance));
  validate_retriangulation_schedule(p.retriangulation);
}

std::string run_parameters_toml(const RunParameters& p)
{
  const char* modes[] = {"constant", "schedule", "adaptive"};
  std::string s;
  s += "# sdflow run parameters, fully resolved (read back by `sdflow run --resume`)\n";
  for (const auto& [key, path] : {std::pair{"input", &p.input}, std::pair{"out", &p.output_dir}})
    if (!path->empty())
      s += fmt::format("{} = {}\n", key, quoted(std::filesystem::absolute(*path).lexically_normal().string()));
  s += fmt::format("steps = {}\n", p.steps);
  if (std::isfinite(p.end_time))
    s += fmt::format("t_end = {}\n", p.end_time);
  s += fmt::format("stop_at_topology_change = {}\n", p.stop_at_topology_change);
  s += fmt::format("time_step = \"{}\"\n", modes[static_cast<int>(p.time_step.mode)]);
  if (p.time_step.mode == TimeStepMode::constant)
    s += fmt::format("tau = {}\n", p.time_step.tau);
  if (p.time_step.mode == TimeStepMode::schedule) {
    if (!p.time_step.schedule_file.empty())
      s += fmt::format("# schedule read from {}\n", p.time_step.schedule_file.string());
    s += "schedule = [";
    for (const auto& e : p.time_step.schedule.entries())
      s += fmt::format("[{}, {}, {}], ", e.first_step, e.last_step, e.tau);
    s += "]\n";
    s += fmt::format("schedule_retries = {}\n", p.time_step.schedule_retries);
  }
  s += fmt::format("beta = {}\n", p.scheme.beta);
  s += fmt::format("curvature = \"{}\"\n", curvature_name(p.scheme.curvature));
  s += fmt::format("mass = \"{}\"\n", mass_name(p.scheme.mass));
  s += fmt::format("extrapolate = {}\n", p.scheme.extrapolate);
  s += fmt::format("solver = \"{}\"\n", p.solver.kind == SolverKind::qr ? "qr" : "cholmod");
  s += fmt::format("factorisation = \"{}\"\n", p.solver.policy == FactorisationPolicy::reuse ? "reuse" : "every_step");
  s += fmt::format("cg_tolerance = {}\n", p.solver.cg_tolerance);
  s += fmt::format("snapshot_every = {}\ncheckpoint_every = {}\n", p.snapshot_every, p.checkpoint_every);
  s += fmt::format("conserve_volume = {}\n", p.conserve_volume);
  s += fmt::format("fixed_boundary = {}\n", p.scheme.boundary == BoundaryMotion::fixed);
  const AdaptiveOptions& a = p.time_step.adaptive;
  s += fmt::format("\n[adaptive]\ninitial_tau = {}\nmax_displacement = {}\ngrowth = {}\nshrink = {}\nsafety = {}\n"
                   "max_volume_change = {}\nmin_tau = {}\nmax_tau = {}\nmax_rejections = {}\ntolerance = {}\n",
                   a.initial_tau, a.max_displacement, a.growth, a.shrink, a.safety, a.max_volume_change, a.min_tau,
                   std::isfinite(a.max_tau) ? a.max_tau : 1e300, a.max_rejections, a.tolerance);
  const RetriangulationSchedule& r = p.retriangulation;
  s += fmt::format("\n[retriangulation]\nenabled = {}\nevery = {}\nmin_angle = {}\nedge_ratio = {}\ndegraded_fraction = {}\n"
                   "always = {}\n"
                   "edge_length = {}\nremesh_iterations = {}\nneighbours = {}\nfill_holes = {}\nmax_hole_length = {}\n"
                   "min_component_faces = {}\nmin_component_thickness = {}\nedges_per_radius = {}\n"
                   "min_edge_fraction = {}\nrestore_volume = {}\ncurved_projection = {}\n",
                   r.enabled, r.every, r.min_angle_deg, r.edge_ratio, r.degraded_fraction, r.always, r.pipeline.target_edge_length,
                   r.pipeline.remesh_iterations, r.pipeline.normals.neighbours, r.pipeline.fill_holes,
                   r.pipeline.max_hole_length, r.pipeline.min_component_faces, r.pipeline.min_component_thickness,
                   r.pipeline.edges_per_radius, r.pipeline.min_edge_fraction, r.restore_volume,
                   r.pipeline.curved_projection);
  s += fmt::format("\n[reference_sphere]\ncentre = [{}, {}, {}]\nradius = {}\n", p.reference_centre.x(),
                   p.reference_centre.y(), p.reference_centre.z(), p.reference_radius);
  return s;
}

} // namespace sdflow
