#include "sdflow/run/simulation.h"

#include "sdflow/errors.h"
#include "sdflow/io/io.h"
#include "sdflow/io/repair.h"
#include "sdflow/io/vtk.h"
#include "sdflow/log.h"
#include "sdflow/run/checkpoint.h"
#include "sdflow/run/run_lock.h"
#include "sdflow/stopwatch.h"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>
#include <string_view>

namespace sdflow {
namespace {

using Clock = std::chrono::steady_clock;

constexpr auto flush_interval = std::chrono::seconds(2);

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

//! metrics.csv's text with the `energy` column, added empty to the rows of an earlier version's file.
std::string with_energy_column(const std::string& metrics)
{
  const std::string legacy = std::string(metrics_header_without_energy) + '\n';
  if (metrics.rfind(legacy, 0) != 0)
    return metrics;
  std::string text = std::string(metrics_header) + '\n';
  std::istringstream rows(metrics.substr(legacy.size()));
  for (std::string row; std::getline(rows, row);)
    text += row + ",\n";
  return text;
}

//! timings.csv's text with the `retriangulation_other` column, added empty to the rows of a file an
//! earlier version wrote (its header lacks it; the column follows `volume_restoration`, the 16th).
std::string with_retriangulation_other_column(const std::string& timings)
{
  constexpr std::string_view legacy =
      "step,total,operators,assembly,factorisation,solve,acceptance,retriangulation_check,merge,remesh,"
      "intersections,normals,reconstruction,holes,components,volume_restoration,output,other,cpu,side_by_side\n";
  if (timings.rfind(legacy, 0) != 0)
    return timings;
  std::string text = std::string(timings_header) + '\n';
  std::istringstream rows(timings.substr(legacy.size()));
  for (std::string row; std::getline(rows, row);) {
    std::size_t at = std::string::npos; // the 16th comma, after volume_restoration
    for (std::size_t k = 0, from = 0; k < 16; ++k, from = at + 1)
      if ((at = row.find(',', from)) == std::string::npos)
        break;
    text += at == std::string::npos ? row + '\n' : row.substr(0, at) + "," + row.substr(at) + '\n';
  }
  return text;
}

//! The stages' wall time summed over the steps of this process, for the line that ends a run.
class TimingSummary {
public:
  void add(const StepTimes& t, double output)
  {
    const auto& p = t.pipeline;
    const double re_triangulation = p.merge + p.remesh + p.intersections + p.normals + p.reconstruction + p.holes +
                                    p.components + t.volume_restoration + t.retriangulation_other;
    const double parts[] = {t.operators, t.assembly, t.factorisation, t.solve, t.acceptance,
                            t.retriangulation_check, re_triangulation, output};
    for (std::size_t i = 0; i < std::size(parts); ++i)
      seconds_[i] += parts[i];
    total_ += t.total + output;
    side_by_side_ += t.side_by_side;
  }

  //! "time by stage: 41.2 s; solve 18.3 s (44%), ..." in the order of timings.csv. Stages that ran
  //! side by side on two threads both count that time: the parts then add up to the wall time
  //! plus those seconds, which the line states, and the percentages are of that sum.
  std::string line() const
  {
    static constexpr const char* names[] = {"operators", "assembly", "factorisation", "solve", "acceptance",
                                            "intersection and quality check", "re-triangulation", "output"};
    const double counted = total_ + side_by_side_;
    const auto percent = [counted](double s) { return counted > 0 ? 100 * s / counted : 0.0; };
    std::string text = fmt::format("time by stage: {:.3g} s in all", total_);
    if (side_by_side_ > 0)
      text += fmt::format(" (stages side by side on two threads for {:.3g} s, counted in each: the parts add up "
                          "to {:.3g} s)", side_by_side_, counted);
    double accounted = 0;
    for (std::size_t i = 0; i < std::size(names); ++i) {
      text += fmt::format("; {} {:.3g} s ({:.0f}%)", names[i], seconds_[i], percent(seconds_[i]));
      accounted += seconds_[i];
    }
    const double other = std::max(0.0, counted - accounted); // timer resolution aside, never below 0
    return text + fmt::format("; other {:.3g} s ({:.0f}%)", other, percent(other));
  }

private:
  double seconds_[8] = {};
  double total_ = 0;
  double side_by_side_ = 0;
};

//! The run directory of one flow: it observes the flow's steps and writes what simulation.h lists.
class RunRecorder {
public:
  //! Take `dir` for a run (created if need be, locked): refused when it is not a directory, is in
  //! use, or (unless `resuming`) already holds a run.
  RunRecorder(const RunParameters& parameters, bool resuming) : run_(parameters), dir_(parameters.output_dir)
  {
    if (dir_.empty())
      throw InvalidParameter("no output directory given for the run");
    if (!resuming)
      prepare_directory();
    lock_.emplace(dir_);
    if (!resuming &&
        (std::filesystem::exists(dir_ / "metrics.csv") || std::filesystem::exists(dir_ / "checkpoint.bin")))
      throw InvalidParameter(fmt::format("{} already holds a run: resume it (sdflow run --resume {}) or choose "
                                         "another output directory", dir_.string(), dir_.string()));
  }

  bool has_checkpoint() const { return std::filesystem::exists(dir_ / "checkpoint.bin"); }
  Checkpoint checkpoint() const { return read_checkpoint(dir_ / "checkpoint.bin"); }

  //! A run with no checkpoint was stopped before its first one: all it wrote is step 0, so
  //! starting again from the same surface gives the run it would have been.
  Mesh restart_surface(const RunParameters& p)
  {
    const std::filesystem::path step0 = dir_ / "snapshots" / "step_000000.ply";
    const std::filesystem::path source = std::filesystem::exists(step0) ? step0 : p.input;
    if (source.empty())
      throw IoError(fmt::format("{}: no checkpoint, no step-0 snapshot and no input in run.toml: nothing to resume "
                                "from; start the run again", dir_.string()));
    logger().warn("{}: no checkpoint yet (the run was stopped before its first one): starting again at step 0 "
                  "from {}", dir_.string(), source.string());
    prepare_directory();
    return source == p.input && p.repair ? read_mesh_or_repair(source).mesh : read_mesh(source).mesh;
  }

  //! Step 0: the resolved parameters, the first metrics row, snapshot and checkpoint.
  void begin(const SurfaceDiffusion& flow)
  {
    snapshots_.clear();
    metrics_ = std::string(metrics_header) + '\n';
    timings_ = std::string(timings_header) + '\n';
    write_atomically(dir_ / "run.toml", [&](std::ostream& out) { out << run_parameters_toml(with_flow_options(run_, flow.options())); });
    const FlowMetrics metrics = flow.metrics();
    log_event(flow, fmt::format("start: {} vertices, {} faces, {} components", metrics.vertices, metrics.faces,
                                metrics.components));
    metrics_ += metrics_row(0, flow.time(), 0, metrics, {});
    snapshot(flow);
    save(flow);
  }

  //! Continue the files of a checkpointed run: metrics.csv and events.log cut back to its step.
  void resume(const SurfaceDiffusion& flow, const Checkpoint& checkpoint)
  {
    snapshots_ = checkpoint.snapshots;
    metrics_ = with_energy_column(read_truncated(dir_ / "metrics.csv", "", flow.steps(), true));
    timings_ = std::filesystem::exists(dir_ / "timings.csv")
                   ? with_retriangulation_other_column(read_truncated(dir_ / "timings.csv", "", flow.steps(), true))
                   : std::string(timings_header) + '\n';
    events_ = read_truncated(dir_ / "events.log", "step ", flow.steps(), false);
    write_atomically(dir_ / "run.toml", [&](std::ostream& out) { out << run_parameters_toml(with_flow_options(run_, flow.options())); });
    log_event(flow, fmt::format("resumed from the checkpoint at t = {}", flow.time()));
  }

  //! After each accepted step: its notes and metrics row; a snapshot and a checkpoint when due.
  void record(SurfaceDiffusion& flow, const StepRecord& step)
  {
    Stopwatch watch;
    take_notes(flow);
    metrics_ += metrics_row(flow.steps(), flow.time(), step.tau, flow.metrics(), event_names(step.events));
    const bool last = flow.finished();
    if (last || (run_.snapshot_every > 0 && flow.steps() % run_.snapshot_every == 0))
      snapshot(flow);
    // The row's output time: the files written since the last row (that row's flush and
    // checkpoint, this step's metrics and snapshot), as a row is written before the files it is in.
    const double output = pending_output_ + watch.restart();
    timings_ += timings_row(flow.steps(), step.times, output);
    summary_.add(step.times, output);
    if (last || flow.steps() % run_.checkpoint_every == 0)
      save(flow);
    else if (Clock::now() - last_flush_ > flush_interval)
      flush();
    pending_output_ = watch.seconds();
  }

  //! Stop between steps: a checkpoint of the last accepted step, as an uninterrupted run would
  //! have written had its checkpoint interval ended there.
  void interrupted(const SurfaceDiffusion& flow)
  {
    log_event(flow, "interrupted: checkpoint written, continue with --resume");
    save(flow);
  }

  void stopped(SurfaceDiffusion& flow, const std::string& reason)
  {
    take_notes(flow);
    log_event(flow, fmt::format("stopped: {}", reason));
    log_event(flow, summary_.line());
    flush();
  }

  void finished(const SurfaceDiffusion& flow)
  {
    log_event(flow, fmt::format("finished at t = {}", flow.time()));
    log_event(flow, summary_.line());
    flush();
  }

private:
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

  void take_notes(SurfaceDiffusion& flow)
  {
    for (const FlowNote& note : flow.take_notes())
      events_ += note.line() + '\n';
  }

  void snapshot(const SurfaceDiffusion& flow)
  {
    const std::string name = fmt::format("step_{:06d}", flow.steps());
    const FlowOperators& op = flow.operators();
    // H and N (PLY: quality, nx ny nz) are those the next step uses; w is the last step's.
    const std::vector<VertexField> fields = {{"H", op.curvature}, {"N", op.normals}, {"w", flow.velocity()}};
    write_mesh(flow.mesh(), dir_ / "snapshots" / (name + ".ply"), {.encoding = Encoding::binary, .vertex_fields = fields});
    write_vtp(flow.mesh(), fields, dir_ / "snapshots" / (name + ".vtp"));
    const std::filesystem::path file = std::filesystem::path("snapshots") / (name + ".vtp");
    if (snapshots_.empty() || snapshots_.back().file != file)
      snapshots_.push_back({flow.time(), file});
    write_pvd(snapshots_, dir_ / "series.pvd");
  }

  void flush()
  {
    write_atomically(dir_ / "metrics.csv", [&](std::ostream& out) { out << metrics_; });
    write_atomically(dir_ / "timings.csv", [&](std::ostream& out) { out << timings_; });
    write_atomically(dir_ / "events.log", [&](std::ostream& out) { out << events_; });
    last_flush_ = Clock::now();
  }

  //! Flush the logs first: a checkpoint must never be ahead of metrics.csv.
  void save(const SurfaceDiffusion& flow)
  {
    flush();
    Checkpoint c;
    static_cast<FlowState&>(c) = flow.state();
    c.snapshots = snapshots_;
    write_checkpoint(c, dir_ / "checkpoint.bin");
  }

  void log_event(const SurfaceDiffusion& flow, const std::string& message)
  {
    const std::string line = FlowNote{.step = flow.steps(), .time = flow.time(), .text = message}.line();
    logger().info("{}", line);
    events_ += line + '\n';
  }

  RunParameters run_; // as given: its own fields, and the flow's options before the flow resolved them
  std::filesystem::path dir_;
  std::optional<RunLock> lock_;
  std::vector<SeriesEntry> snapshots_;
  std::string metrics_, events_, timings_;
  Clock::time_point last_flush_ = Clock::now();
  double pending_output_ = 0;
  TimingSummary summary_;
};

//! The events a run reports besides its rows (SimulationResult::events).
bool is_notable(StepEventKind kind)
{
  return kind != StepEventKind::start && kind != StepEventKind::rejected && kind != StepEventKind::remeshed;
}

//! Step `flow` to its end (or until `options.stop_requested`), recording every step.
SimulationResult run(SurfaceDiffusion& flow, RunRecorder& recorder, const SimulationOptions& options)
{
  SimulationResult result;
  try {
    while (!flow.finished()) {
      if (options.stop_requested && options.stop_requested()) {
        recorder.interrupted(flow);
        result.interrupted = true;
        break;
      }
      const StepRecord step = flow.step();
      recorder.record(flow, step);
      for (const StepEvent& e : step.events)
        if (is_notable(e.kind))
          result.events.push_back(e);
      if (options.progress)
        options.progress(step);
    }
  } catch (const SolverFailure& e) {
    recorder.stopped(flow, e.what());
    throw;
  }
  if (!result.interrupted)
    recorder.finished(flow);
  result.mesh = flow.mesh();
  result.steps = flow.steps();
  result.time = flow.time();
  result.rejected_trials = flow.rejected_trials();
  result.factorisations = flow.factorisations();
  return result;
}

} // namespace

std::string metrics_row(long step, double time, double tau, const FlowMetrics& m, const std::string& event)
{
  return fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", step, time, tau, m.vertices, m.faces,
                     m.components, m.genus, m.area, m.volume, m.mean_curvature, m.curvature_deviation_pct, m.d1, m.d2,
                     m.debris_volume, event, m.energy);
}

std::string timings_row(long step, const StepTimes& t, double output)
{
  const auto& p = t.pipeline;
  const double total = t.total + output;
  const double other = total + t.side_by_side - (t.operators + t.assembly + t.factorisation + t.solve + t.acceptance +
                                t.retriangulation_check + p.merge + p.remesh + p.intersections + p.normals +
                                p.reconstruction + p.holes + p.components + t.volume_restoration +
                                t.retriangulation_other + output);
  return fmt::format("{},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},"
                     "{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f}\n",
                     step, total, t.operators, t.assembly, t.factorisation, t.solve, t.acceptance,
                     t.retriangulation_check, p.merge, p.remesh, p.intersections, p.normals, p.reconstruction, p.holes,
                     p.components, t.volume_restoration, t.retriangulation_other, output, other, t.cpu, t.side_by_side);
}

SimulationResult run_simulation(const Mesh& initial, const SimulationOptions& options)
{
  // The parameters were checked when they were made (CheckedRunParameters). The flow is made
  // before the directory is taken: a mesh it refuses leaves no run behind.
  SurfaceDiffusion flow(initial, options.parameters.flow(), options.retriangulate);
  RunRecorder recorder(*options.parameters, false);
  recorder.begin(flow);
  return run(flow, recorder, options);
}

SimulationResult resume_simulation(const SimulationOptions& options)
{
  // The parameters were checked when they were made (CheckedRunParameters).
  RunRecorder recorder(*options.parameters, true);
  if (!recorder.has_checkpoint()) {
    const Mesh initial = recorder.restart_surface(*options.parameters);
    SurfaceDiffusion flow(initial, options.parameters.flow(), options.retriangulate);
    recorder.begin(flow);
    SimulationResult result = run(flow, recorder, options);
    result.restarted = true;
    return result;
  }
  const Checkpoint checkpoint = recorder.checkpoint();
  SurfaceDiffusion flow(checkpoint, options.parameters.flow(), options.retriangulate);
  recorder.resume(flow, checkpoint);
  return run(flow, recorder, options);
}

} // namespace sdflow
