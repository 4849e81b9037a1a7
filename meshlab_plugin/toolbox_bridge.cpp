#include "toolbox_bridge.h"

#include "sdflow/errors.h"
#include "sdflow/flow/boundary_condition.h"
#include "sdflow/flow/scheme.h"
#include "sdflow/flow/surface_diffusion.h"
#include "sdflow/geometry/curvature.h"
#include "sdflow/geometry/normals.h"
#include "sdflow/geometry/quality.h"
#include "sdflow/io/validate.h"
#include "sdflow/log.h"
#include "sdflow/retri/pipeline.h"
#include "sdflow/run/parameter_schema.h"
#include "sdflow/run/parameters.h"
#include "sdflow/run/run_input.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/sinks/base_sink.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <mutex>

namespace sdflow::meshlab {
namespace {

//! Forwards each toolbox log line to the reporter.
class ReporterSink : public spdlog::sinks::base_sink<std::mutex> {
public:
  explicit ReporterSink(std::function<void(LogLevel, const std::string&)> log) : log_(std::move(log)) {}

protected:
  void sink_it_(const spdlog::details::log_msg& message) override
  {
    LogLevel level = LogLevel::info;
    if (message.level <= spdlog::level::debug)
      level = LogLevel::debug;
    else if (message.level == spdlog::level::warn)
      level = LogLevel::warning;
    else if (message.level >= spdlog::level::err)
      level = LogLevel::error;
    log_(level, std::string(message.payload.data(), message.payload.size()));
  }
  void flush_() override {}

private:
  std::function<void(LogLevel, const std::string&)> log_;
};

//! Routes the toolbox's logger to a reporter for one bridge call, and silences it afterwards so no
//! later message reaches a reporter that no longer exists.
class LoggerScope {
public:
  explicit LoggerScope(const Reporter& reporter)
  {
    auto logger = reporter.log ? std::make_shared<spdlog::logger>("sdflow", std::make_shared<ReporterSink>(reporter.log))
                               : std::make_shared<spdlog::logger>("sdflow");
    logger->set_level(spdlog::level::info);
    set_logger(std::move(logger));
  }
  ~LoggerScope() { set_logger(std::make_shared<spdlog::logger>("sdflow")); }
  LoggerScope(const LoggerScope&) = delete;
  LoggerScope& operator=(const LoggerScope&) = delete;
};

PolygonSoup to_soup(const Surface& surface)
{
  PolygonSoup soup;
  soup.points.reserve(surface.points.size());
  for (const auto& p : surface.points)
    soup.points.emplace_back(p[0], p[1], p[2]);
  soup.polygons.reserve(surface.triangles.size());
  for (const auto& t : surface.triangles)
    soup.polygons.push_back({t[0], t[1], t[2]});
  return soup;
}

//! The surface as `sdflow` would have it after reading a file: validated, oriented outward.
Mesh checked_mesh(const Surface& surface, const std::string& name)
{
  BuiltMesh built;
  try {
    built = build_mesh(to_soup(surface), name);
  } catch (const MeshValidationError& e) {
    // The exception's message is capped; the log gets every finding with its code.
    for (const Finding& finding : e.findings())
      logger().error("{}: {}", finding.code, finding.message);
    throw;
  }
  // Repairs are worth a warning; build_mesh itself logs the one notable information (a flip).
  for (const Finding& finding : built.findings)
    if (finding.severity == Severity::warning)
      logger().warn("{}: {}", finding.code, finding.message);
  return std::move(built.mesh);
}

//! `mesh` with the given per-vertex normals and mean curvature.
ShadedSurface shaded(const Mesh& mesh, const VertexVectors& normals, const Eigen::VectorXd& curvature)
{
  ShadedSurface result;
  const VertexVectors positions = vertex_positions(mesh);
  const auto triangles = face_indices(mesh);
  for (Eigen::Index v = 0; v < positions.rows(); ++v) {
    result.surface.points.push_back({positions(v, 0), positions(v, 1), positions(v, 2)});
    result.normals.push_back({normals(v, 0), normals(v, 1), normals(v, 2)});
    result.mean_curvature.push_back(curvature[v]);
  }
  for (Eigen::Index f = 0; f < triangles.rows(); ++f)
    result.surface.triangles.push_back({triangles(f, 0), triangles(f, 1), triangles(f, 2)});
  return result;
}

} // namespace

double mean_edge_length(const Surface& input)
{
  // An invalid surface gets its reasons reported when a filter is applied, not here.
  const LoggerScope silent{Reporter{}};
  try {
    return mesh_quality(checked_mesh(input, "mesh")).edge_mean;
  } catch (const Error&) {
    return 0;
  }
}

double natural_time_step(const double mean_edge_length) { return std::pow(mean_edge_length, 4); }

std::vector<DialogParameter> diffusion_parameters(const double mean_edge_length, const MeshlabFilter filter)
{
  using Kind = DialogParameter::Kind;
  using Default = MeshlabParameter::Default;
  std::vector<DialogParameter> list;
  for (const ParameterEntry& e : parameter_schema()) {
    const MeshlabParameter& m = e.meshlab;
    if (!m.offered_by(filter))
      continue;
    DialogParameter d{.name = m.name, .label = m.label, .help = m.help.empty() ? e.help : m.help};
    const ParameterValue value = m.value ? *m.value : e.get(RunParameters{});
    if (m.boolean_choices) {
      d.kind = Kind::boolean;
      d.flag = std::get<std::string>(value) == m.boolean_choices->second;
    } else if (e.type == ParameterType::integer) {
      d.kind = Kind::integer;
      d.number = static_cast<double>(std::get<long>(value));
    } else if (e.type == ParameterType::real) {
      d.kind = Kind::real;
      d.number = m.source == Default::mean_edge_length    ? mean_edge_length
                 : m.source == Default::natural_time_step ? natural_time_step(mean_edge_length)
                                                           : std::get<double>(value);
    } else if (e.type == ParameterType::boolean) {
      d.kind = Kind::boolean;
      d.flag = std::get<bool>(value);
    } else if (e.type == ParameterType::choice) {
      d.kind = Kind::choice;
      d.choices = e.choices;
      d.choice = static_cast<int>(std::find(e.choices.begin(), e.choices.end(), std::get<std::string>(value)) -
                                  e.choices.begin());
    } else if (e.type == ParameterType::text) {
      d.kind = Kind::text;
      d.text = std::get<std::string>(value);
    } else if (e.type == ParameterType::reals) {
      d.kind = Kind::text;
      d.text = fmt::format("{}", fmt::join(std::get<std::vector<double>>(value), ", "));
    } else {
      throw std::logic_error("the dialog has no parameter of type " + type_name(e.type) + " (" + e.key + ")");
    }
    list.push_back(std::move(d));
  }
  return list;
}

namespace {

//! "0 (a), 1 (b) or 2 (c)", for messages about an index.
std::string numbered(const std::vector<std::string>& names)
{
  std::string list;
  for (std::size_t i = 0; i < names.size(); ++i)
    list += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + std::to_string(i) + " (" + names[i] + ")";
  return list;
}

//! The numbers of a dialog's text, separated by commas or spaces ("1, 1, 4"); throws
//! InvalidParameter naming the parameter at the first word that is not a number.
std::vector<double> dialog_numbers(const MeshlabParameter& m, const std::string& text)
{
  std::vector<double> numbers;
  std::size_t at = 0;
  while ((at = text.find_first_not_of(", \t", at)) != std::string::npos) {
    const std::size_t end = std::min(text.find_first_of(", \t", at), text.size());
    const std::string word = text.substr(at, end - at);
    double number = 0;
    const auto [last, error] = std::from_chars(word.data(), word.data() + word.size(), number);
    if (error != std::errc() || last != word.data() + word.size())
      throw InvalidParameter(fmt::format("{} ({}) must be numbers separated by commas, got \"{}\" in \"{}\"", m.label,
                                         m.name, word, text));
    numbers.push_back(number);
    at = end;
  }
  return numbers;
}

//! The value of `e` the dialog's `value` stands for.
ParameterValue dialog_value(const ParameterEntry& e, const DialogValue& value)
{
  const MeshlabParameter& m = e.meshlab;
  if (m.boolean_choices)
    return value.flag ? m.boolean_choices->second : m.boolean_choices->first;
  switch (e.type) {
  case ParameterType::integer: return static_cast<long>(std::llround(value.number));
  case ParameterType::real: return value.number;
  case ParameterType::boolean: return value.flag;
  case ParameterType::choice:
    if (value.choice < 0 || value.choice >= static_cast<int>(e.choices.size()))
      throw InvalidParameter(fmt::format("{} must be {}, got {}", m.name, numbered(e.choices), value.choice));
    return e.choices[value.choice];
  case ParameterType::text: return value.text;
  case ParameterType::reals: return dialog_numbers(m, value.text);
  default: break;
  }
  throw std::logic_error("the dialog has no parameter of type " + type_name(e.type));
}

//! The run `filter`'s settings describe: sdflow's defaults, the substrate filter's boundary, then
//! each setting as its scenario key.
RunParameters run_parameters(const MeshlabFilter filter, const DiffusionSettings& settings)
{
  std::vector<const ParameterEntry*> given;
  for (const auto& [name, _] : settings) {
    const ParameterEntry* e = find_meshlab_parameter(name, filter);
    if (!e)
      throw InvalidParameter(fmt::format("{} has no parameter {}", meshlab_filter_name(filter), name));
    given.push_back(e);
  }
  RunParameters p;
  if (filter == MeshlabFilter::substrate)
    p.scheme.boundary = BoundaryCondition::substrate;
  for (const auto order : {ParameterEntry::Order::first, ParameterEntry::Order::normal, ParameterEntry::Order::last})
    for (const ParameterEntry* e : given)
      if (e->order == order) {
        e->set(p, dialog_value(*e, settings.at(e->meshlab.name)));
        for (const auto& implication : e->implies)
          if (!implication.flag_only)
            find_parameter(implication.key)->set(p, implication.value);
      }
  for (const ParameterEntry* e : given) {
    if (e->in_use && !e->in_use(p))
      continue;
    const ParameterRange& range = e->meshlab.range.text().empty() ? e->range : e->meshlab.range;
    const ParameterValue value = e->get(p);
    const double number = std::holds_alternative<long>(value) ? static_cast<double>(std::get<long>(value))
                          : std::holds_alternative<double>(value) ? std::get<double>(value)
                                                                  : 0.0;
    if ((std::holds_alternative<long>(value) || std::holds_alternative<double>(value)) && !range.contains(number))
      throw InvalidParameter(fmt::format("{} ({}) must be {}, got {}", e->meshlab.label, e->meshlab.name, range.text(),
                                         toml_text(value)));
  }
  return p;
}

} // namespace

ShadedSurface surface_diffusion(const Surface& input, const std::string& name, const MeshlabFilter filter,
                                const DiffusionSettings& settings, const Reporter& reporter)
{
  const LoggerScope scope(reporter);
  // The same flow as `sdflow run` with the same options, in memory.
  RunParameters p = run_parameters(filter, settings);
  Mesh initial = checked_mesh(input, name);
  check_run_input(initial, p, name, FrontEnd::meshlab, run_input_limits(FrontEnd::meshlab, false));
  SurfaceDiffusion flow(initial, p);
  while (!flow.finished()) {
    const StepRecord record = flow.step();
    if (reporter.progress)
      reporter.progress(static_cast<int>(100 * record.step / p.steps),
                        fmt::format("surface diffusion: step {} of {}, τ = {:.3g}", record.step, p.steps, record.tau));
  }
  logger().info("surface diffusion: {} steps to t = {:.6g} ({} rejected trial steps)", flow.steps(), flow.time(),
                flow.rejected_trials());
  // The H the flow steps with and `sdflow run` writes: the cotangent H divides by the flow's vertex areas.
  return shaded(flow.mesh(), flow.operators().normals, flow.operators().curvature);
}

RetriangulationSettings default_retriangulation_settings()
{
  const RetriangulationOptions defaults;
  return {.edge_length = defaults.edge_length, .remesh_iterations = defaults.remesh_iterations,
          .always_rebuild = defaults.always_rebuild, .fill_holes = defaults.fill_holes,
          .min_component_faces = defaults.min_component_faces};
}

ShadedSurface retriangulate_surface(const Surface& input, const std::string& name,
                                    const RetriangulationSettings& settings, const Reporter& reporter)
{
  const LoggerScope scope(reporter);
  const Mesh mesh = checked_mesh(input, name);
  RetriangulationOptions options;
  options.edge_length = settings.edge_length;
  options.remesh_iterations = settings.remesh_iterations;
  options.always_rebuild = settings.always_rebuild;
  options.fill_holes = settings.fill_holes;
  options.min_component_faces = settings.min_component_faces;
  const RetriangulationResult r = retriangulate(mesh, options);
  logger().info("re-triangulation to edge length {:.6g}: {} → {} vertices; {}; {} boundary loop(s) left",
                r.edge_length, mesh.n_vertices(), r.mesh.n_vertices(), retriangulation_summary(r), r.open_holes);
  const VertexVectors normals = vertex_normals(r.mesh);
  return shaded(r.mesh, normals, mean_curvature(r.mesh, normals));
}

} // namespace sdflow::meshlab
