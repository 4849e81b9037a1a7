//! `sdflow run`: evolve a surface by surface diffusion flow into a run directory (flow/simulation.h).
//!   sdflow run --input MESH --out DIR [--steps N] [--t-end T]
//!              [--tau T | --schedule FILE [--schedule-retries N] | --adaptive]
//!              [--preset paper|default] [--beta B] [--curvature NAME] [--mass NAME] [--extrapolate]
//!              [--tolerance E] [--solver cholmod|qr] [--edges-per-radius N]
//!              [--snapshot-every K] [--checkpoint-every K] [--conserve-volume] [--fixed-boundary]
//!              [--retriangulate [--edge-length L]] [--quiet]
//!   sdflow run SCENARIO.toml [flags]     (flags override the file's keys)
//!   sdflow run --resume DIR [--steps N] [--t-end T]
//! SIGINT / SIGTERM stop the run after the current step with a checkpoint (exit 130 / 143).

#include "exit_status.h"
#include "verbs.h"

#include "sdflow/errors.h"
#include "sdflow/flow/simulation.h"
#include "sdflow/io/io.h"
#include "sdflow/limits.h"
#include "sdflow/log.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <unistd.h>

namespace sdflow::cli {
namespace {

struct RunArguments {
  std::string scenario, input, out, resume, schedule, solver, curvature, mass, preset;
  long steps = 0, snapshot_every = 0, checkpoint_every = 0;
  int schedule_retries = 0;
  double end_time = 0, tau = 0, beta = 0, edge_length = 0, tolerance = 0, edges_per_radius = 0;
  bool adaptive = false, extrapolate = false, stop_at_topology_change = false, conserve_volume = false, fixed_boundary = false,
       retriangulate = false, quiet = false, force = false;
  std::map<std::string, CLI::Option*> given;
  bool has(const std::string& name) const { return given.at(name)->count() > 0; }
};

//! Progress on stderr: a bar rewritten in place on a terminal, a plain line every 10 s otherwise.
class Progress {
public:
  Progress(const RunParameters& p, bool quiet) : p_(p), quiet_(quiet), tty_(::isatty(::fileno(stderr)) != 0) {}

  void operator()(const StepRecord& r)
  {
    if (quiet_)
      return;
    const auto now = Clock::now();
    if (!started_) {
      start_ = last_ = now;
      first_step_ = r.step - 1;
      started_ = true;
    }
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double rate = elapsed > 0 ? (r.step - first_step_) / elapsed : 0.0;
    double fraction = 0;
    if (p_.steps > 0)
      fraction = static_cast<double>(r.step) / static_cast<double>(p_.steps);
    if (std::isfinite(p_.end_time))
      fraction = std::max(fraction, r.time / p_.end_time);
    fraction = std::min(fraction, 1.0);
    const double done_since_start = fraction - start_fraction(r);
    const double eta = done_since_start > 0 ? elapsed * (1 - fraction) / done_since_start : 0.0;
    const std::string text = fmt::format("step {} t={:.6g} τ={:.3g} {:.2f} steps/s ETA {}", r.step, r.time, r.tau, rate,
                                         clock_text(eta));
    if (tty_) {
      constexpr int width = 30;
      const int filled = static_cast<int>(fraction * width);
      std::cerr << '\r' << '[' << std::string(filled, '#') << std::string(width - filled, '.') << "] "
                << fmt::format("{:3.0f}% ", 100 * fraction) << text << "\033[K" << std::flush;
    } else if (now - last_ >= std::chrono::seconds(10)) {
      std::cerr << fmt::format("{:.0f}% ", 100 * fraction) << text << '\n';
      last_ = now;
    }
  }

  void finish() const
  {
    if (tty_ && started_ && !quiet_)
      std::cerr << '\n';
  }

private:
  using Clock = std::chrono::steady_clock;
  double start_fraction(const StepRecord& r)
  {
    if (!have_start_fraction_) {
      start_fraction_ = 0;
      if (p_.steps > 0)
        start_fraction_ = static_cast<double>(r.step - 1) / static_cast<double>(p_.steps);
      if (std::isfinite(p_.end_time))
        start_fraction_ = std::max(start_fraction_, (r.time - r.tau) / p_.end_time);
      have_start_fraction_ = true;
    }
    return start_fraction_;
  }
  static std::string clock_text(double seconds)
  {
    const long s = std::lround(seconds);
    return fmt::format("{}:{:02d}:{:02d}", s / 3600, (s / 60) % 60, s % 60);
  }

  const RunParameters& p_;
  bool quiet_, tty_;
  bool started_ = false, have_start_fraction_ = false;
  long first_step_ = 0;
  double start_fraction_ = 0;
  Clock::time_point start_, last_;
};

void apply_flags(const RunArguments& a, RunParameters& p)
{
  if (a.has("--preset")) apply_preset(a.preset, p);
  if (a.has("--input")) p.input = a.input;
  if (a.has("--out")) p.output_dir = a.out;
  if (a.has("--steps")) p.steps = a.steps;
  if (a.has("--t-end")) p.end_time = a.end_time;
  if (a.has("--stop-at-topology-change")) p.stop_at_topology_change = true;
  if (a.has("--beta")) p.scheme.beta = a.beta;
  if (a.has("--curvature")) p.scheme.curvature = curvature_options(a.curvature);
  if (a.has("--mass")) p.scheme.mass = vertex_mass(a.mass);
  if (a.has("--extrapolate")) p.scheme.extrapolate = true;
  if (a.has("--tolerance")) {
    p.time_step.adaptive.tolerance = a.tolerance;
    p.scheme.extrapolate = true;
  }
  if (a.has("--edges-per-radius")) p.retriangulation.pipeline.edges_per_radius = a.edges_per_radius;
  if (a.has("--snapshot-every")) p.snapshot_every = a.snapshot_every;
  if (a.has("--checkpoint-every")) p.checkpoint_every = a.checkpoint_every;
  if (a.has("--conserve-volume")) p.conserve_volume = true;
  if (a.has("--fixed-boundary")) p.scheme.boundary = BoundaryMotion::fixed;
  if (a.has("--retriangulate")) p.retriangulation.enabled = true;
  if (a.has("--edge-length")) p.retriangulation.pipeline.target_edge_length = a.edge_length;
  if (a.has("--solver")) p.solver.kind = a.solver == "qr" ? SolverKind::qr : SolverKind::cholmod;
  if (a.has("--schedule-retries")) p.time_step.schedule_retries = a.schedule_retries;
  if (a.has("--tau")) {
    p.time_step.mode = TimeStepMode::constant;
    p.time_step.tau = a.tau;
  } else if (a.has("--schedule")) {
    p.time_step.mode = TimeStepMode::schedule;
    p.time_step.schedule_file = std::filesystem::absolute(a.schedule);
    p.time_step.schedule = read_schedule(a.schedule);
  } else if (a.has("--adaptive")) {
    p.time_step.mode = TimeStepMode::adaptive;
  }
}

//! The signal that asked the run to stop (0: none). Set by the handler, read between steps.
volatile std::sig_atomic_t stop_signal = 0;

void request_stop(int signal) { stop_signal = signal; }

//! SIGINT and SIGTERM ask the run to stop after the current step (with a checkpoint); the
//! handler only sets a flag, and is reset by the first signal, so a second one kills at once;
//! interrupted system calls restart.
void install_stop_handlers()
{
  struct sigaction action {};
  action.sa_handler = request_stop;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND | SA_RESTART;
  ::sigaction(SIGINT, &action, nullptr);
  ::sigaction(SIGTERM, &action, nullptr);
}

void run(const RunArguments& a)
{
  RunParameters p;
  const bool resuming = a.has("--resume");
  if (resuming) {
    if (a.has("--input") || a.has("--tau") || a.has("--schedule") || a.has("--adaptive") || a.has("--beta") ||
        a.has("--schedule-retries") || a.has("--curvature") || a.has("--mass") || a.has("--extrapolate") ||
        a.has("--preset") || a.has("--tolerance") || a.has("--edges-per-radius") ||
        a.has("--solver") || a.has("--retriangulate") || a.has("--edge-length") || !a.scenario.empty())
      throw InvalidParameter("--resume continues a run with its own parameters (run.toml): only --steps, --t-end, "
                             "--snapshot-every and --checkpoint-every may be changed");
    if (!std::filesystem::exists(std::filesystem::path(a.resume) / "run.toml"))
      throw InvalidParameter(fmt::format("{} holds no run to resume (no run.toml: it was stopped before writing "
                                         "anything, or is not a run directory); start the run again with --out",
                                         a.resume));
    read_run_parameters(std::filesystem::path(a.resume) / "run.toml", p);
    p.output_dir = a.resume;
  } else if (!a.scenario.empty()) {
    read_run_parameters(a.scenario, p);
  }
  apply_flags(a, p);
  if (!resuming && p.input.empty())
    throw InvalidParameter("no input mesh: give --input MESH or `input` in the scenario file");
  if (p.output_dir.empty())
    throw InvalidParameter("no run directory: give --out DIR or `out` in the scenario file");
  validate_run_parameters(p);
  const SizeLimits limits{.force = a.force};
  check_count(p.steps, limits.max_steps, "--steps", limits);

  Progress progress(p, a.quiet);
  install_stop_handlers();
  SimulationOptions options{.parameters = p, .progress = std::ref(progress),
                            .stop_requested = [] { return stop_signal != 0; }};
  SimulationResult result;
  try {
    if (resuming) {
      result = resume_simulation(options);
    } else {
      BuiltMesh built = read_mesh(p.input);
      for (const auto& f : built.findings)
        logger().warn("{}: {}", p.input.string(), f.message);
      if (p.retriangulation.enabled)
        check_remeshed_size(built.mesh, p.retriangulation.pipeline.target_edge_length,
                            fmt::format("run --retriangulate --edge-length {}",
                                        p.retriangulation.pipeline.target_edge_length),
                            limits);
      result = run_simulation(built.mesh, options);
    }
  } catch (...) {
    progress.finish();
    throw;
  }
  progress.finish();
  if (result.interrupted) {
    const int signal = stop_signal;
    std::cerr << fmt::format("sdflow: {} received: stopped after step {} (t = {:.6g}) with a checkpoint; continue "
                             "with: sdflow run --resume {}\n",
                             signal == SIGTERM ? "SIGTERM" : signal == SIGINT ? "SIGINT" : "a signal", result.steps,
                             result.time, p.output_dir.string());
    throw ExitStatus{128 + signal};
  }
  std::cout << fmt::format("{}: {} steps, t = {:.6g}, {} vertices; {} rejected trials, {} factorisations\n",
                           p.output_dir.string(), result.steps, result.time, result.mesh.n_vertices(),
                           result.rejected_trials, result.factorisations);
}

} // namespace

void add_run_verb(CLI::App& app)
{
  auto args = std::make_shared<RunArguments>();
  CLI::App* verb = app.add_subcommand("run", "Evolve a surface by surface diffusion flow into a run directory");
  auto& g = args->given;
  verb->add_option("scenario", args->scenario, "Scenario TOML file (keys documented in flow/parameters.h)")
      ->check(CLI::ExistingFile);
  g["--input"] = verb->add_option("--input", args->input, "Initial mesh (OFF, OBJ, PLY, STL)")->check(CLI::ExistingFile);
  g["--out"] = verb->add_option("--out", args->out, "Run directory (must not hold a run yet)");
  g["--steps"] = verb->add_option("--steps", args->steps, "Stop after N steps")->check(CLI::PositiveNumber);
  g["--t-end"] = verb->add_option("--t-end", args->end_time, "Stop at time T")->check(CLI::PositiveNumber);
  g["--stop-at-topology-change"] =
      verb->add_flag("--stop-at-topology-change", args->stop_at_topology_change,
                     "Also stop after the first step that changes the component count or the genus (with "
                     "--retriangulate): event times of pinch-offs, seals and fusions");
  g["--tau"] = verb->add_option("--tau", args->tau, "Constant time step τ")->check(CLI::PositiveNumber);
  g["--schedule"] = verb->add_option("--schedule", args->schedule, "τ schedule (CSV first,last,tau or TOML)")
                        ->check(CLI::ExistingFile);
  g["--schedule-retries"] = verb->add_option("--schedule-retries", args->schedule_retries,
                                             "Halve a schedule's τ up to N times when a step turns triangles over "
                                             "(default 0: stop)")
                                 ->check(CLI::Range(0, 60));
  g["--adaptive"] = verb->add_flag("--adaptive", args->adaptive, "Adaptive τ (the default)");
  g["--tau"]->excludes(g["--schedule"])->excludes(g["--adaptive"]);
  g["--schedule"]->excludes(g["--adaptive"]);
  g["--beta"] = verb->add_option("--beta", args->beta, "Implicitness β (default 0.5; 0 = explicit)")
                    ->check(CLI::NonNegativeNumber);
  g["--preset"] = verb->add_option("--preset", args->preset,
                                   "paper: the paper's scheme exactly (eq. 9 H, Voronoi areas, plain steps, uniform "
                                   "re-triangulation, no volume restoration); default: sdflow's. Other flags override it")
                      ->check(CLI::IsMember({"paper", "default"}));
  g["--curvature"] =
      verb->add_option("--curvature", args->curvature,
                       "Mean curvature: cotangent (H = ½ N·ΔX, default), normal_integral (eq. 9, the paper's) or "
                       "normal_integral_angle_sum")
          ->check(CLI::IsMember({"cotangent", "normal_integral", "normal_integral_angle_sum"}));
  g["--mass"] = verb->add_option("--mass", args->mass,
                                 "Vertex areas of the Laplacian: voronoi (eq. 10, default) or volume_gradient")
                     ->check(CLI::IsMember({"voronoi", "volume_gradient"}));
  g["--extrapolate"] = verb->add_flag("--extrapolate", args->extrapolate,
                                      "Richardson-extrapolate each step: second order in τ, three solves a step");
  g["--tolerance"] = verb->add_option("--tolerance", args->tolerance,
                                      "Adaptive τ with a bound on the extrapolated step's local error estimate, "
                                      "relative to the local edge length (implies --extrapolate)")
                         ->check(CLI::PositiveNumber);
  g["--edges-per-radius"] =
      verb->add_option("--edges-per-radius", args->edges_per_radius,
                       "Re-triangulation: edges per radius of curvature where finer than ℓ (default 4; 0: uniform ℓ)")
          ->check(CLI::NonNegativeNumber);
  g["--solver"] = verb->add_option("--solver", args->solver, "Linear solver: cholmod (default) or qr (paper's, slow)")
                      ->check(CLI::IsMember({"cholmod", "qr"}));
  g["--snapshot-every"] = verb->add_option("--snapshot-every", args->snapshot_every,
                                           "Snapshot every K steps (0: first and last only; default 10)")
                              ->check(CLI::NonNegativeNumber);
  g["--checkpoint-every"] = verb->add_option("--checkpoint-every", args->checkpoint_every,
                                             "Checkpoint every K steps (default 10)")
                                ->check(CLI::PositiveNumber);
  g["--conserve-volume"] = verb->add_flag("--conserve-volume", args->conserve_volume,
                                          "Restore each closed component's volume after every step");
  g["--fixed-boundary"] = verb->add_flag("--fixed-boundary", args->fixed_boundary, "Hold boundary vertices in place");
  g["--retriangulate"] = verb->add_flag(
      "--retriangulate", args->retriangulate,
      "Re-triangulate between steps when the surface intersects itself or its triangles degrade (paper §3.2.1)");
  g["--edge-length"] = verb->add_option("--edge-length", args->edge_length,
                                        "Target edge length of the re-triangulation (default: the initial mean)")
                           ->check(CLI::PositiveNumber);
  g["--resume"] = verb->add_option("--resume", args->resume, "Continue the run in DIR from its checkpoint")
                      ->check(CLI::ExistingDirectory);
  verb->add_flag("--quiet", args->quiet, "No progress output");
  verb->add_flag("--force", args->force, "Skip the plausibility limits (steps, size of the re-triangulated surface)");
  verb->callback([args] { run(*args); });
}

} // namespace sdflow::cli
