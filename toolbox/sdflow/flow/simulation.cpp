#include "sdflow/flow/simulation.h"

#include "sdflow/errors.h"
#include "sdflow/flow/checkpoint.h"
#include "sdflow/flow/retriangulation.h"
#include "sdflow/flow/run_lock.h"
#include "sdflow/flow/scheme.h"
#include "sdflow/flow/volume.h"
#include "sdflow/geometry/laplacian.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/io.h"
#include "sdflow/io_vtk.h"
#include "sdflow/log.h"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>

namespace sdflow {
namespace {

using Triangles = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;
using Clock = std::chrono::steady_clock;

constexpr auto flush_interval = std::chrono::seconds(2);
constexpr double end_time_tolerance = 1e-12; // relative: the last step is clipped to land on t_end

//! The mesh rebuilt from its arrays, so that a run and its resumption from a checkpoint (which
//! stores the arrays) traverse identical halfedge structures and round identically.
Mesh canonical(const Mesh& mesh) { return make_mesh(vertex_positions(mesh), face_indices(mesh)); }

//! Mean length of the edges at each vertex: the local scale of the displacement bound.
Eigen::VectorXd mean_edge_lengths(const Mesh& mesh)
{
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(mesh.n_vertices());
  Eigen::VectorXd count = Eigen::VectorXd::Zero(mesh.n_vertices());
  for (auto e : mesh.edges()) {
    const double length = mesh.calc_edge_length(e);
    const int a = e.v0().idx(), b = e.v1().idx();
    sum[a] += length;
    sum[b] += length;
    count[a] += 1;
    count[b] += 1;
  }
  return sum.cwiseQuotient(count.cwiseMax(1.0));
}

//! Components, closedness and total genus, recomputed only when the connectivity changes.
struct Topology {
  std::vector<int> face_component;
  int count = 0;
  std::vector<bool> closed;
  int genus = 0;
};

Topology topology_of(const Mesh& mesh)
{
  Topology t;
  t.face_component = face_component_ids(mesh, &t.count);
  for (const auto& c : component_topology(mesh)) {
    t.closed.push_back(c.closed());
    t.genus += c.genus;
  }
  return t;
}

std::string join_events(const std::vector<std::string>& events)
{
  std::string s;
  for (const auto& e : events)
    s += (s.empty() ? "" : "+") + e;
  return s;
}

long leading_step(const std::string& line, const std::string& prefix)
{
  if (line.compare(0, prefix.size(), prefix) != 0)
    return -1;
  long step = -1;
  std::istringstream(line.substr(prefix.size())) >> step;
  return step;
}

//! The lines of `file` whose leading step number (after `prefix`) is at most `last_step`.
std::string read_truncated(const std::filesystem::path& file, const std::string& prefix, long last_step,
                           bool keep_first_line)
{
  std::ifstream in(file);
  std::string text, line;
  for (bool first = true; std::getline(in, line); first = false) {
    if ((first && keep_first_line) || (leading_step(line, prefix) >= 0 && leading_step(line, prefix) <= last_step))
      text += line + '\n';
  }
  return text;
}

class Runner {
public:
  explicit Runner(const SimulationOptions& options)
      : options_(options), p_(options.parameters), dir_(p_.output_dir), solver_(p_.solver),
        half_solver_(p_.solver), controller_(p_.time_step)
  {
    validate_run_parameters(p_);
    if (dir_.empty())
      throw InvalidParameter("no output directory given for the run");
  }

  void start(const Mesh& initial)
  {
    prepare_directory();
    lock_.emplace(dir_);
    if (std::filesystem::exists(dir_ / "metrics.csv") || std::filesystem::exists(dir_ / "checkpoint.bin"))
      throw InvalidParameter(fmt::format("{} already holds a run: resume it (sdflow run --resume {}) or choose "
                                         "another output directory", dir_.string(), dir_.string()));
    begin(initial);
  }

  void begin(const Mesh& initial)
  {
    mesh_ = canonical(initial);
    renew_connectivity();
    prepare_retriangulation();
    last_w_ = Eigen::VectorXd::Zero(mesh_.n_vertices());
    metrics_ = std::string(metrics_header) + '\n';
    write_atomically(dir_ / "run.toml", [&](std::ostream& out) { out << run_parameters_toml(p_); });
    log_event(fmt::format("start: {} vertices, {} faces, {} components", mesh_.n_vertices(), mesh_.n_faces(),
                          topology_.count));
    op_ = flow_operators(mesh_, p_.scheme, &*cache_);
    append_metrics(0, {});
    snapshot();
    save();
  }

  //! Resume from the checkpoint, or start again at step 0 when the run has none yet (true).
  bool resume()
  {
    lock_.emplace(dir_);
    if (!std::filesystem::exists(dir_ / "checkpoint.bin")) {
      restart();
      return true;
    }
    const Checkpoint c = read_checkpoint(dir_ / "checkpoint.bin");
    step_ = c.step;
    time_ = c.time;
    mesh_ = make_mesh(c.positions, c.triangles);
    renew_connectivity();
    prepare_retriangulation();
    previous_w_ = c.previous_w;
    last_w_ = c.previous_w.size() == static_cast<Eigen::Index>(mesh_.n_vertices())
                  ? c.previous_w
                  : Eigen::VectorXd::Zero(mesh_.n_vertices());
    controller_ = TimeStepController(p_.time_step, c.time_step);
    tolerated_degraded_ = c.tolerated_degraded;
    snapshots_ = c.snapshots;
    // Refactorise the anchors' systems: the preconditioners are then the ones the uninterrupted run
    // would be using, so the CG iterates (and every later decision) are identical.
    if (c.has_anchor) {
      restore_solver(solver_, c.anchor_positions, c.anchor_tau_beta, c.triangles, c.solver);
      has_anchor_ = true;
      anchor_positions_ = c.anchor_positions;
      anchor_tau_beta_ = c.anchor_tau_beta;
    }
    if (c.has_half_anchor) {
      restore_solver(half_solver_, c.half_anchor_positions, c.half_anchor_tau_beta, c.triangles, c.half_solver);
      has_half_anchor_ = true;
      half_anchor_positions_ = c.half_anchor_positions;
      half_anchor_tau_beta_ = c.half_anchor_tau_beta;
    }
    metrics_ = read_truncated(dir_ / "metrics.csv", "", step_, true);
    events_ = read_truncated(dir_ / "events.log", "step ", step_, false);
    write_atomically(dir_ / "run.toml", [&](std::ostream& out) { out << run_parameters_toml(p_); });
    log_event(fmt::format("resumed from the checkpoint at t = {}", time_));
    op_ = flow_operators(mesh_, p_.scheme, &*cache_);
    return false;
  }

  //! Stop between steps: a checkpoint of the last accepted step, as an uninterrupted run would
  //! have written had its checkpoint interval ended there.
  void interrupt()
  {
    log_event("interrupted: checkpoint written, continue with --resume");
    save();
    result_.interrupted = true;
  }

  SimulationResult run()
  {
    try {
      while (!finished()) {
        if (options_.stop_requested && options_.stop_requested()) {
          interrupt();
          return result();
        }
        advance();
      }
    } catch (const SolverFailure& e) {
      log_event(fmt::format("stopped: {}", e.what()));
      flush();
      throw;
    }
    log_event(fmt::format("finished at t = {}", time_));
    flush();
    return result();
  }

  SimulationResult& result()
  {
    result_.mesh = mesh_;
    result_.steps = step_;
    result_.time = time_;
    return result_;
  }

private:
  void restore_solver(FlowSolver& solver, const VertexVectors& positions, double tau_beta, const Triangles& triangles,
                      const SolverState& state)
  {
    Mesh anchor = make_mesh(positions, triangles);
    const FlowOperators anchor_op = flow_operators(anchor, p_.scheme, &*cache_);
    solver.restore(FlowSystem{anchor_op.laplacian, anchor_op.areas, anchor_op.held, tau_beta}, state);
  }

  //! The run directory and its snapshots folder, created if need be; a path that cannot be one
  //! (an existing file, a path under a file, a name too long) is refused with the reason.
  void prepare_directory()
  {
    std::error_code ec;
    const auto status = std::filesystem::status(dir_, ec);
    if (std::filesystem::exists(status) && !std::filesystem::is_directory(status))
      throw InvalidParameter(fmt::format("{} exists and is not a directory: the run directory must be a new or an "
                                         "empty directory", dir_.string()));
    std::filesystem::create_directories(dir_ / "snapshots", ec);
    if (ec) {
      const std::string message =
          fmt::format("{}: cannot create the run directory ({})", dir_.string(), ec.message());
      if (ec.value() == ENOSPC || ec.value() == EDQUOT || ec.value() == EROFS || ec.value() == EIO)
        throw EnvironmentFailure(message);
      throw IoError(message);
    }
  }

  //! A run with no checkpoint was stopped inside start(): all it wrote is step 0, so starting
  //! again from the same surface gives the run it would have been.
  void restart()
  {
    const std::filesystem::path step0 = dir_ / "snapshots" / "step_000000.ply";
    const bool from_snapshot = std::filesystem::exists(step0);
    const std::filesystem::path source = from_snapshot ? step0 : p_.input;
    if (source.empty())
      throw IoError(fmt::format("{}: no checkpoint, no step-0 snapshot and no input in run.toml: nothing to resume "
                                "from; start the run again", dir_.string()));
    logger().warn("{}: no checkpoint yet (the run was stopped before its first one): starting again at step 0 "
                  "from {}", dir_.string(), source.string());
    prepare_directory();
    const Mesh initial = read_mesh(source).mesh;
    snapshots_.clear();
    begin(initial);
    result_.restarted = true;
  }

  bool finished() const
  {
    return (p_.steps > 0 && step_ >= p_.steps) ||
           (std::isfinite(p_.end_time) && time_ >= p_.end_time * (1 - end_time_tolerance)) ||
           topology_changed_;
  }

  //! The hook: the caller's, or the one of the parameters' schedule with its ℓ fixed now.
  void prepare_retriangulation()
  {
    if (options_.retriangulate) {
      retriangulate_ = options_.retriangulate;
      return;
    }
    RetriangulationSchedule& schedule = p_.retriangulation;
    if (!schedule.enabled)
      return;
    if (!(schedule.pipeline.target_edge_length > 0)) {
      double sum = 0;
      for (const auto e : mesh_.edges())
        sum += mesh_.calc_edge_length(e);
      schedule.pipeline.target_edge_length = sum / static_cast<double>(std::max<std::size_t>(mesh_.n_edges(), 1));
    }
    retriangulate_ = make_retriangulation_hook(schedule);
  }

  //! The hook's failure stops the run like an unstable step: the files written so far stay valid.
  RetriangulationReport call_retriangulation(bool force)
  {
    try {
      RetriangulationReport report = retriangulate_(mesh_, {step_, time_, tolerated_degraded_, force});
      if (report.degraded_left >= 0)
        tolerated_degraded_ = report.degraded_left;
      return report;
    } catch (const SolverFailure&) {
      throw;
    } catch (const Error& e) {
      throw SolverFailure(fmt::format("re-triangulation after step {} failed: {}", step_, e.what()));
    }
  }

  void renew_connectivity()
  {
    triangles_ = face_indices(mesh_);
    topology_ = topology_of(mesh_);
    cache_.emplace(mesh_);
  }

  double automatic_tau(const Eigen::VectorXd& edge_lengths) const
  {
    // The explicit velocity ΔH bounds the semi-implicit one (the inverse of I + τβΔ² is a
    // contraction), so this τ meets the displacement bound on the first step.
    const Eigen::VectorXd speed = op_.rhs.cwiseQuotient(op_.areas).cwiseAbs();
    double tau = std::numeric_limits<double>::infinity();
    for (Eigen::Index v = 0; v < speed.size(); ++v)
      if (speed[v] > 0 && (op_.held.empty() || !op_.held[v]))
        tau = std::min(tau, edge_lengths[v] / speed[v]);
    const AdaptiveOptions& a = p_.time_step.adaptive;
    if (std::isinf(tau)) // a surface at rest: the scale of the bi-Laplacian's time step, h⁴
      return std::pow(edge_lengths.mean(), 4);
    return a.safety * a.max_displacement * tau;
  }

  StepCheck check(const StepResult& trial, double tau, const Eigen::VectorXd& edge_lengths,
                  const std::vector<double>& volumes) const
  {
    StepCheck c;
    const VertexVectors& next = trial.positions;
    if (!next.allFinite()) {
      c.non_finite = true;
      return c;
    }
    c.displacement_ratio = (tau * trial.w.cwiseAbs()).cwiseQuotient(edge_lengths).maxCoeff();
    if (trial.error.rows() > 0)
      c.error_estimate = trial.error.rowwise().norm().cwiseQuotient(edge_lengths).maxCoeff();
    const VertexVectors& now = positions_;
    for (Eigen::Index f = 0; f < triangles_.rows(); ++f) {
      const auto normal = [&](const VertexVectors& x) {
        const Eigen::Vector3d a = x.row(triangles_(f, 0)), b = x.row(triangles_(f, 1)), d = x.row(triangles_(f, 2));
        return Eigen::Vector3d((b - a).cross(d - a));
      };
      if (normal(now).dot(normal(next)) <= 0)
        ++c.inverted_triangles;
    }
    const std::vector<double> after = component_volumes(next, triangles_, topology_.face_component, topology_.count);
    for (int k = 0; k < topology_.count; ++k)
      if (topology_.closed[k] && volumes[k] != 0)
        c.volume_change = std::max(c.volume_change, std::abs(after[k] - volumes[k]) / std::abs(volumes[k]));
    if (p_.time_step.mode == TimeStepMode::adaptive) {
      c.displacement_exceeded = c.displacement_ratio > p_.time_step.adaptive.max_displacement;
      c.volume_exceeded = c.volume_change > p_.time_step.adaptive.max_volume_change;
      c.error_exceeded = p_.time_step.adaptive.tolerance > 0 && c.error_estimate > p_.time_step.adaptive.tolerance;
    }
    return c;
  }

  //! Trials of step `next_step` until the controller accepts one (returned: its τ); throws
  //! SolverFailure as the controller does.
  double trial_step(long next_step, StepResult& trial, StepRecord& record, int& rejections,
                    std::vector<double>& volumes)
  {
    positions_ = vertex_positions(mesh_);
    const Eigen::VectorXd edge_lengths = mean_edge_lengths(mesh_);
    volumes = component_volumes(positions_, triangles_, topology_.face_component, topology_.count);
    const bool need_automatic_tau = p_.time_step.mode == TimeStepMode::adaptive &&
                                    controller_.state().next_tau == 0 && p_.time_step.adaptive.initial_tau == 0;
    const double automatic = need_automatic_tau ? automatic_tau(edge_lengths) : 0.0;
    const double time_left = std::isfinite(p_.end_time) ? p_.end_time - time_ : std::numeric_limits<double>::infinity();
    for (;;) {
      const double tau = controller_.propose(next_step, automatic, time_left);
      trial = p_.scheme.extrapolate
                  ? extrapolated_step(mesh_, op_, tau, p_.scheme, solver_, half_solver_, &*cache_, previous_w_)
                  : solve_step(mesh_, op_, tau, p_.scheme.beta, solver_, previous_w_);
      record.cg_iterations += trial.solve.iterations;
      result_.factorisations += trial.factorisations;
      if (trial.solve.factorised) {
        has_anchor_ = p_.solver.kind == SolverKind::cholmod;
        anchor_positions_ = trial.factorised_positions;
        anchor_tau_beta_ = trial.factorised_tau_beta;
      }
      if (trial.half_factorised) {
        has_half_anchor_ = p_.solver.kind == SolverKind::cholmod;
        half_anchor_positions_ = trial.half_factorised_positions;
        half_anchor_tau_beta_ = trial.half_factorised_tau_beta;
      }
      if (trial.factorisations > 0) {
        record.factorised = true;
        logger().debug("step {}: {} factorisations (τ = {})", next_step, trial.factorisations, tau);
      }
      const StepCheck c = check(trial, tau, edge_lengths, volumes);
      if (controller_.judge(next_step, tau, c))
        return tau;
      ++rejections;
      ++result_.rejected_trials;
      log_event(fmt::format("rejected τ = {}: {}", tau, c.describe()), next_step);
    }
  }

  //! Take the re-triangulated mesh: new connectivity, fresh factorisations, its events.
  void adopt_retriangulation(const RetriangulationReport& report, std::vector<std::string>& events)
  {
    const int components = topology_.count, genus = topology_.genus;
    mesh_ = canonical(mesh_);
    renew_connectivity();
    topology_changed_ =
        topology_changed_ || (p_.stop_at_topology_change && (topology_.count != components || topology_.genus != genus));
    solver_.forget_factorisation();
    half_solver_.forget_factorisation();
    has_anchor_ = has_half_anchor_ = false;
    previous_w_.resize(0);
    last_w_ = Eigen::VectorXd::Zero(mesh_.n_vertices());
    std::vector<std::string> these;
    for (const auto& [flag, name] : {std::pair{report.remeshed, "remeshed"}, std::pair{report.surgery, "surgery"},
                                     std::pair{report.split, "split"}, std::pair{report.merged, "merged"}})
      if (flag && std::find(events.begin(), events.end(), name) == events.end()) {
        events.emplace_back(name);
        these.emplace_back(name);
      }
    log_event(fmt::format("re-triangulated ({}): {}", join_events(these), report.detail));
  }

  void advance()
  {
    const long next_step = step_ + 1;
    const TimeStepState controller_before = controller_.state();
    std::vector<std::string> events;
    if (p_.time_step.mode == TimeStepMode::schedule && !p_.time_step.schedule.entries().empty() &&
        next_step == p_.time_step.schedule.entries().back().last_step + 1) {
      const std::string message = fmt::format("the τ schedule ends at step {}: the steps after it repeat its last "
                                              "τ = {}", next_step - 1, p_.time_step.schedule.entries().back().tau);
      logger().warn("{}", message);
      events_ += fmt::format("step {} t={}: {}\n", next_step, time_, message);
    }

    int rejections = 0;
    StepRecord record;
    StepResult trial;
    double tau = 0;
    std::vector<double> volumes;
    // A step that no τ makes acceptable (a triangle beside a closing neck that turns over
    // whatever the step) is retried once after a re-triangulation of the surface it starts from.
    for (bool forced = false;;) {
      try {
        tau = trial_step(next_step, trial, record, rejections, volumes);
        break;
      } catch (const SolverFailure& e) {
        if (!retriangulate_ || forced)
          throw;
        forced = true;
        log_event(fmt::format("no acceptable step ({}): re-triangulating, then trying again", e.what()), next_step);
        RetriangulationReport report = call_retriangulation(true);
        if (!report.changed())
          throw;
        adopt_retriangulation(report, events);
        op_ = flow_operators(mesh_, p_.scheme, &*cache_);
        controller_ = TimeStepController(p_.time_step, {.next_tau = controller_before.next_tau});
      }
    }
    if (rejections > 0)
      events.insert(events.begin(), "rejected");

    set_vertex_positions(mesh_, trial.positions);
    if (p_.conserve_volume) {
      const VolumeRestoration restored = restore_volumes(mesh_, volumes);
      set_vertex_positions(mesh_, restored.positions);
    }
    step_ = next_step;
    time_ += tau;
    previous_w_ = trial.w;
    last_w_ = trial.w;

    if (retriangulate_) {
      const RetriangulationReport report = call_retriangulation(false);
      if (report.changed())
        adopt_retriangulation(report, events);
    }
    op_ = flow_operators(mesh_, p_.scheme, &*cache_);
    record.event = join_events(events);
    append_metrics(tau, record.event);

    const bool last = finished();
    if (last || (p_.snapshot_every > 0 && step_ % p_.snapshot_every == 0))
      snapshot();
    if (last || step_ % p_.checkpoint_every == 0)
      save();
    else if (Clock::now() - last_flush_ > flush_interval)
      flush();

    record.step = step_;
    record.time = time_;
    record.tau = tau;
    record.rejections = rejections;
    if (options_.progress)
      options_.progress(record);
  }

  void append_metrics(double tau, const std::string& event)
  {
    const CurvatureDeviation h = curvature_deviation(op_.curvature, op_.areas);
    const SphereDeviation d = sphere_deviation(mesh_, op_.areas, p_.reference_centre, p_.reference_radius);
    const double area = surface_area(mesh_);
    const double volume = enclosed_volume(mesh_);
    metrics_ += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", step_, time_, tau, mesh_.n_vertices(),
                            mesh_.n_faces(), topology_.count, topology_.genus, area, volume, h.mean, h.deviation_pct,
                            d.d1, d.d2, event);
  }

  void snapshot()
  {
    const std::string name = fmt::format("step_{:06d}", step_);
    write_mesh(mesh_, dir_ / "snapshots" / (name + ".ply"), {.encoding = Encoding::binary});
    write_vtp(mesh_, {{"H", op_.curvature}, {"N", op_.normals}, {"w", last_w_}},
              dir_ / "snapshots" / (name + ".vtp"));
    const std::filesystem::path file = std::filesystem::path("snapshots") / (name + ".vtp");
    if (snapshots_.empty() || snapshots_.back().file != file)
      snapshots_.push_back({time_, file});
    write_pvd(snapshots_, dir_ / "series.pvd");
  }

  void flush()
  {
    write_atomically(dir_ / "metrics.csv", [&](std::ostream& out) { out << metrics_; });
    write_atomically(dir_ / "events.log", [&](std::ostream& out) { out << events_; });
    last_flush_ = Clock::now();
  }

  //! Flush the logs first: a checkpoint must never be ahead of metrics.csv.
  void save()
  {
    flush();
    Checkpoint c;
    c.step = step_;
    c.time = time_;
    c.positions = vertex_positions(mesh_);
    c.triangles = triangles_;
    c.previous_w = previous_w_;
    c.time_step = controller_.state();
    c.solver = solver_.state();
    c.has_anchor = has_anchor_;
    if (has_anchor_)
      c.anchor_positions = anchor_positions_;
    c.anchor_tau_beta = anchor_tau_beta_;
    c.snapshots = snapshots_;
    c.tolerated_degraded = tolerated_degraded_;
    c.half_solver = half_solver_.state();
    c.has_half_anchor = has_half_anchor_;
    if (has_half_anchor_)
      c.half_anchor_positions = half_anchor_positions_;
    c.half_anchor_tau_beta = half_anchor_tau_beta_;
    write_checkpoint(c, dir_ / "checkpoint.bin");
  }

  void log_event(const std::string& message, long step = -1)
  {
    const std::string line = fmt::format("step {} t={}: {}", step < 0 ? step_ : step, time_, message);
    logger().info("{}", line);
    events_ += line + '\n';
  }

  const SimulationOptions& options_;
  std::optional<RunLock> lock_;
  RunParameters p_;
  RetriangulationHook retriangulate_;
  std::filesystem::path dir_;
  FlowSolver solver_, half_solver_; // the half steps of extrapolated steps keep a factor of their own
  TimeStepController controller_;
  Mesh mesh_;
  Triangles triangles_;
  Topology topology_;
  std::optional<CotangentCache> cache_;
  FlowOperators op_;
  VertexVectors positions_;
  long step_ = 0;
  double time_ = 0;
  long tolerated_degraded_ = 0; // see RetriangulationContext
  bool topology_changed_ = false; // with stop_at_topology_change: the run ends after this step
  Eigen::VectorXd previous_w_, last_w_;
  bool has_anchor_ = false, has_half_anchor_ = false;
  VertexVectors anchor_positions_, half_anchor_positions_;
  double anchor_tau_beta_ = 0, half_anchor_tau_beta_ = 0;
  std::vector<SeriesEntry> snapshots_;
  std::string metrics_, events_;
  Clock::time_point last_flush_ = Clock::now();
  SimulationResult result_;
};

} // namespace

SimulationResult run_simulation(const Mesh& initial, const SimulationOptions& options)
{
  Runner runner(options);
  runner.start(initial);
  return runner.run();
}

SimulationResult resume_simulation(const SimulationOptions& options)
{
  Runner runner(options);
  const bool restarted = runner.resume();
  SimulationResult result = runner.run();
  result.restarted = restarted;
  return result;
}

} // namespace sdflow
