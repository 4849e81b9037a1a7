#include "toolbox_bridge.h"

#include "sdflow/errors.h"
#include "sdflow/flow/parameters.h"
#include "sdflow/flow/scheme.h"
#include "sdflow/flow/surface_diffusion.h"
#include "sdflow/geometry/curvature.h"
#include "sdflow/geometry/normals.h"
#include "sdflow/geometry/quality.h"
#include "sdflow/log.h"
#include "sdflow/retri/pipeline.h"
#include "sdflow/io/validate.h"

#include <spdlog/sinks/base_sink.h>
#include <spdlog/spdlog.h>

#include <cmath>
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

std::vector<std::string> curvature_names()
{
  return {curvature_name({.method = CurvatureMethod::cotangent}), curvature_name({}),
          curvature_name({.normalisation = AngleNormalisation::angle_sum})};
}

std::vector<std::string> mass_names()
{
  return {mass_name(VertexMass::voronoi), mass_name(VertexMass::volume_gradient)};
}

ShadedSurface surface_diffusion(const Surface& input, const std::string& name, const DiffusionSettings& settings,
                                const Reporter& reporter)
{
  const LoggerScope scope(reporter);
  if (settings.steps < 1)
    throw InvalidParameter("steps must be at least 1, got " + std::to_string(settings.steps));
  const Mesh initial = checked_mesh(input, name);

  // The same flow as `sdflow run` with the same options, in memory.
  RunParameters p;
  p.steps = settings.steps;
  p.time_step.mode = settings.automatic_tau ? TimeStepMode::adaptive : TimeStepMode::constant;
  p.time_step.tau = settings.automatic_tau ? 0.0 : settings.tau;
  p.scheme.beta = settings.beta;
  p.scheme.boundary = settings.fixed_boundary ? BoundaryMotion::fixed : BoundaryMotion::paper;
  p.scheme.curvature = curvature_options(settings.curvature);
  p.scheme.mass = vertex_mass(settings.mass);
  p.scheme.extrapolate = settings.extrapolate;
  p.conserve_volume = settings.conserve_volume;
  p.retriangulation.enabled = settings.retriangulate;
  p.retriangulation.pipeline.target_edge_length = settings.edge_length;
  SurfaceDiffusion flow(initial, p);
  while (!flow.finished()) {
    const StepRecord record = flow.step();
    if (reporter.progress)
      reporter.progress(static_cast<int>(100 * record.step / settings.steps),
                        fmt::format("surface diffusion: step {} of {}, τ = {:.3g}", record.step, settings.steps,
                                    record.tau));
  }
  logger().info("surface diffusion: {} steps to t = {:.6g} ({} rejected trial steps)", flow.steps(), flow.time(),
                flow.rejected_trials());
  // The H the flow steps with and `sdflow run` writes: the cotangent H divides by the flow's vertex areas.
  return shaded(flow.mesh(), flow.operators().normals, flow.operators().curvature);
}

ShadedSurface retriangulate_surface(const Surface& input, const std::string& name,
                                    const RetriangulationSettings& settings, const Reporter& reporter)
{
  const LoggerScope scope(reporter);
  const Mesh mesh = checked_mesh(input, name);
  RetriangulationOptions options;
  options.target_edge_length = settings.edge_length;
  options.remesh_iterations = settings.remesh_iterations;
  options.always_rebuild = settings.always_rebuild;
  options.fill_holes = settings.fill_holes;
  options.min_component_faces = settings.min_component_faces;
  const RetriangulationResult r = retriangulate(mesh, options);
  logger().info("re-triangulation to edge length {:.6g}: {} vertices, {} component(s) → {} vertices, "
                "{} component(s); {} component(s) joined, {} intersecting face pairs, {} faces removed, {}, "
                "{} debris component(s) dropped, {} boundary loop(s) left",
                r.target_edge_length, mesh.n_vertices(), r.components_before, r.mesh.n_vertices(), r.components_after,
                r.merged_components, r.intersecting_pairs, r.removed_faces,
                r.rebuilt ? fmt::format("rebuilt from the points ({} hole(s) filled)", r.filled_holes)
                          : std::string("not rebuilt (nothing intersected)"),
                r.dropped_components, r.open_holes);
  const VertexVectors normals = vertex_normals(r.mesh);
  return shaded(r.mesh, normals, mean_curvature(r.mesh, normals));
}

} // namespace sdflow::meshlab
