//! `sdflow run`: evolve a surface by surface diffusion flow into a run directory (run/simulation.h).
//!   sdflow run --input MESH --out DIR [--steps N] [--end-time T] [a flag for every scenario key]
//!   sdflow run SCENARIO.toml [flags]     (flags override the file's keys)
//!   sdflow run --resume DIR [--steps N] [--end-time T] [the other flags the schema marks resumable]
//!   sdflow run --help-scenario           (the table of keys and flags, markdown, as in README)
//!   sdflow run --help-meshlab            (the MeshLab filter's parameters, markdown, as in README)
//! The flags, their checks and the resume rules come from the schema (run/parameter_schema.h).
//! SIGINT / SIGTERM stop the run after the current step with a checkpoint (exit 130 / 143).

#include "common_options.h"
#include "exit_status.h"
#include "json_report.h"
#include "numbers.h"
#include "repair_hint.h"
#include "verbs.h"

#include "sdflow/errors.h"
#include "sdflow/io/io.h"
#include "sdflow/limits.h"
#include "sdflow/log.h"
#include "sdflow/run/parameter_schema.h"
#include "sdflow/run/run_input.h"
#include "sdflow/run/simulation.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <toml++/toml.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <iostream>
#include <unistd.h>

namespace sdflow::cli {
namespace {

//! The flag of one schema entry (run/parameter_schema.h): its option, where CLI11 puts the value,
//! and the options of its shorthands (`--adaptive`).
struct SchemaFlag {
  const ParameterEntry* entry = nullptr;
  CLI::Option* option = nullptr;
  long integer = 0;
  double real = 0;
  bool boolean = false;
  std::string text;
  std::vector<double> numbers; // a point or reals
  std::vector<std::pair<CLI::Option*, const ParameterEntry::Shorthand*>> shorthands;

  bool given() const { return option->count() > 0; }

  //! The value given, as the entry's type.
  ParameterValue value() const
  {
    switch (entry->type) {
    case ParameterType::integer: return integer;
    case ParameterType::real: return real;
    case ParameterType::boolean: return boolean;
    case ParameterType::choice:
    case ParameterType::text: return text;
    case ParameterType::path: return std::filesystem::path(text);
    case ParameterType::point: return Eigen::Vector3d(numbers.at(0), numbers.at(1), numbers.at(2));
    case ParameterType::reals: return numbers;
    case ParameterType::schedule: break;
    }
    return ScheduleSetting{std::filesystem::absolute(text), read_schedule(text).entries()};
  }

  //! The flags given on the command line for this entry, for messages.
  std::vector<std::string> given_names() const
  {
    std::vector<std::string> names;
    if (given())
      names.push_back(entry->flag);
    for (const auto& [shorthand, _] : shorthands)
      if (shorthand->count() > 0)
        names.push_back(shorthand->get_name());
    return names;
  }
};

struct RunArguments {
  std::string scenario, resume;
  bool force = false, help_scenario = false, help_meshlab = false, json = false;
  CLI::Option* resume_option = nullptr;
  std::deque<SchemaFlag> flags; // one per schema entry, in the schema's order (a deque: stable addresses)
};

//! Progress on stderr: a bar rewritten in place on a terminal, a plain line every 10 s otherwise;
//! none under -q (the log level above info).
class Progress {
public:
  explicit Progress(const RunParameters& p)
      : p_(p), quiet_(!logger().should_log(spdlog::level::info)), tty_(::isatty(::fileno(stderr)) != 0)
  {
  }

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
  //! H:MM:SS; an estimate beyond what a run can take (or not a number) as "--:--:--", which
  //! also keeps the rounding to an integer from overflowing.
  static std::string clock_text(double seconds)
  {
    constexpr double longest = 1e4 * 3600; // ten thousand hours
    if (!(seconds >= 0 && seconds < longest))
      return "--:--:--";
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

//! Set an implied parameter (`--tau` implies time_step = "constant").
void apply_implication(const ParameterEntry::Implication& implication, RunParameters& p)
{
  find_parameter(implication.key)->set(p, implication.value);
}

//! The flags given, over the parameters: the preset first, the time-step mode last, as a scenario's keys.
void apply_flags(const RunArguments& a, RunParameters& p)
{
  for (const auto order : {ParameterEntry::Order::first, ParameterEntry::Order::normal, ParameterEntry::Order::last})
    for (const SchemaFlag& flag : a.flags) {
      const ParameterEntry& e = *flag.entry;
      if (e.order != order)
        continue;
      if (flag.given()) {
        e.set(p, flag.value());
        for (const auto& implication : e.implies)
          apply_implication(implication, p);
      }
      for (const auto& [option, shorthand] : flag.shorthands)
        if (option->count() > 0)
          e.set(p, shorthand->value);
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
  const bool resuming = a.resume_option->count() > 0;
  if (resuming) {
    std::vector<std::string> refused, allowed;
    for (const SchemaFlag& flag : a.flags) {
      if (flag.entry->resumable) {
        allowed.push_back(flag.entry->flag);
        continue;
      }
      const std::vector<std::string> given = flag.given_names();
      refused.insert(refused.end(), given.begin(), given.end());
    }
    if (!a.scenario.empty())
      refused.push_back("a scenario file");
    if (!refused.empty())
      throw InvalidParameter(fmt::format("--resume continues a run with its own parameters (run.toml): only {} may be "
                                         "changed, not {}",
                                         fmt::join(allowed, ", "), fmt::join(refused, ", ")));
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
  // The samples' large meshes are made by a script beside them, not shipped.
  if (const auto maker = std::filesystem::path(a.scenario).parent_path() / "make_meshes.sh";
      !resuming && !a.scenario.empty() && !std::filesystem::exists(p.input) && std::filesystem::exists(maker))
    throw IoError(fmt::format("{}: no such file: this sample's mesh is made by {}; run it once with the sdflow "
                              "binary: {} SDFLOW",
                              p.input.string(), maker.string(), shell_word(maker.string())));
  if (p.output_dir.empty())
    throw InvalidParameter("no run directory: give --out DIR or `out` in the scenario file");
  const CheckedRunParameters checked(p); // once, before the input is read
  const SizeLimits limits = run_input_limits(FrontEnd::command_line, a.force);
  if (resuming)
    check_count(p.steps, limits.max_steps, "--steps", limits);

  Progress progress(p);
  install_stop_handlers();
  SimulationOptions options{.parameters = checked, .progress = std::ref(progress),
                            .stop_requested = [] { return stop_signal != 0; }};
  SimulationResult result;
  try {
    if (resuming) {
      result = resume_simulation(options);
    } else {
      BuiltMesh built = p.repair ? read_mesh_or_repair(p.input) : read_mesh_or_suggest_repair(p.input);
      for (const auto& f : built.findings)
        logger().warn("{}: {}", p.input.string(), f.message);
      check_run_input(built.mesh, p, p.input.string(), FrontEnd::command_line, limits);
      options.parameters = CheckedRunParameters(p); // with the ℓ the input checks may have chosen
      result = run_simulation(built.mesh, options);
    }
  } catch (...) {
    progress.finish();
    throw;
  }
  progress.finish();
  const int signal = result.interrupted ? static_cast<int>(stop_signal) : 0;
  const char* signal_name = signal == SIGTERM ? "SIGTERM" : signal == SIGINT ? "SIGINT" : "a signal";
  if (a.json) {
    toml::table root{{"output", p.output_dir.string()},
                     {"steps", static_cast<int64_t>(result.steps)},
                     {"time", result.time},
                     {"vertices", static_cast<int64_t>(result.mesh.n_vertices())},
                     {"faces", static_cast<int64_t>(result.mesh.n_faces())},
                     {"rejected_trials", static_cast<int64_t>(result.rejected_trials)},
                     {"factorisations", static_cast<int64_t>(result.factorisations)},
                     {"interrupted", result.interrupted}};
    toml::array events;
    for (const StepEvent& e : result.events)
      events.push_back(event_json(e));
    root.insert("events", std::move(events));
    if (result.interrupted)
      root.insert("signal", signal_name);
    print_json(std::move(root));
  }
  if (result.interrupted) {
    std::cerr << fmt::format("sdflow: {} received: stopped after step {} (t = {:.6g}) with a checkpoint; continue "
                             "with: sdflow run --resume {}\n",
                             signal_name, result.steps, result.time, p.output_dir.string());
    throw ExitStatus{128 + signal};
  }
  if (!a.json)
    std::cout << fmt::format("{}: {} steps, t = {:.6g}, {} vertices; {} rejected trials, {} factorisations\n",
                             p.output_dir.string(), result.steps, result.time, result.mesh.n_vertices(),
                             result.rejected_trials, result.factorisations);
}

} // namespace

namespace {

//! The entry's range as a check of the flag's text (the text is a plain number: numbers.h).
CLI::Validator range_check(const ParameterEntry& e)
{
  return CLI::Validator(
      [&e](std::string& text) -> std::string {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || e.range.contains(value))
          return "";
        return fmt::format("{} must be {}, got {}", e.key, e.range.text(), text);
      },
      "", "");
}

std::string flag_help(const ParameterEntry& e)
{
  std::vector<std::string> notes;
  if (const std::string d = e.default_text(); d != "none")
    notes.push_back("default " + d);
  if (const std::string range = e.range.text(); !range.empty())
    notes.push_back(range);
  notes.push_back("scenario key " + e.key);
  return fmt::format("{} [{}]", e.help, fmt::join(notes, "; "));
}

//! One option per schema entry (and per shorthand), in the entry's section's group of the help.
void add_schema_flags(CLI::App& verb, RunArguments& args)
{
  for (const ParameterEntry& e : parameter_schema()) {
    SchemaFlag& flag = args.flags.emplace_back();
    flag.entry = &e;
    std::string names = e.flag;
    for (const std::string& alias : e.flag_aliases)
      names += "," + alias;
    const std::string help = flag_help(e);
    switch (e.type) {
    case ParameterType::integer:
      flag.option = verb.add_option(names, flag.integer, help)->check(range_check(e));
      break;
    case ParameterType::real:
      flag.option = verb.add_option(names, flag.real, help)->check(range_check(e));
      if (e.range.infinite_allowed)
        flag.option->type_name(kRealOrInfinity);
      break;
    case ParameterType::boolean:
      flag.option = verb.add_flag(names + ",!--no-" + e.flag.substr(2), flag.boolean, help);
      break;
    case ParameterType::choice:
      flag.option = verb.add_option(names, flag.text, help)->check(CLI::IsMember(e.choices));
      break;
    case ParameterType::text:
      flag.option = verb.add_option(names, flag.text, help)->type_name("TEXT");
      break;
    case ParameterType::path:
    case ParameterType::schedule:
      flag.option = verb.add_option(names, flag.text, help);
      if (e.existing_file)
        flag.option->check(CLI::ExistingFile);
      break;
    case ParameterType::point:
      flag.option = verb.add_option(names, flag.numbers, help)->expected(3)->delimiter(',')->type_name("X,Y,Z");
      break;
    case ParameterType::reals:
      flag.option = verb.add_option(names, flag.numbers, help)->delimiter(',')->type_name("A,B,...");
      break;
    }
    const std::string group = e.section().empty() ? "Run parameters" : "[" + e.section() + "] parameters";
    flag.option->group(group);
    for (const auto& shorthand : e.shorthands) {
      CLI::Option* option = verb.add_flag(shorthand.flag, shorthand.help)->group(group);
      flag.shorthands.emplace_back(option, &shorthand);
    }
  }
  // Flags that imply different values of one parameter exclude each other: --tau, --schedule, --adaptive.
  std::vector<std::tuple<CLI::Option*, std::string, std::string>> implying; // option, key, value
  for (const SchemaFlag& flag : args.flags) {
    for (const auto& implication : flag.entry->implies)
      implying.emplace_back(flag.option, implication.key, toml_text(implication.value));
    for (const auto& [option, shorthand] : flag.shorthands)
      implying.emplace_back(option, flag.entry->key, toml_text(ParameterValue(shorthand->value)));
  }
  for (std::size_t i = 0; i < implying.size(); ++i)
    for (std::size_t j = i + 1; j < implying.size(); ++j)
      if (std::get<1>(implying[i]) == std::get<1>(implying[j]) && std::get<2>(implying[i]) != std::get<2>(implying[j]))
        std::get<0>(implying[i])->excludes(std::get<0>(implying[j]));
}

} // namespace

void add_run_verb(CLI::App& app)
{
  auto args = std::make_shared<RunArguments>();
  CLI::App* verb = app.add_subcommand("run", "Evolve a surface by surface diffusion flow into a run directory");
  verb->add_option("scenario", args->scenario,
                   "Scenario TOML file: the keys of `sdflow run --help-scenario`; flags override them")
      ->check(CLI::ExistingFile);
  args->resume_option = verb->add_option("--resume", args->resume, "Continue the run in DIR from its checkpoint")
                            ->check(CLI::ExistingDirectory);
  verb->add_flag("--force", args->force, "Skip the plausibility limits (steps, size of the re-triangulated surface)");
  verb->add_flag("--help-scenario", args->help_scenario,
                 "Print the table of scenario keys and their flags (markdown, as in README) and exit");
  verb->add_flag("--help-meshlab", args->help_meshlab,
                 "Print the table of the MeshLab filter's parameters and their flags (markdown, as in README) and exit");
  add_json_flag(*verb, args->json);
  add_schema_flags(*verb, *args);
  verb->callback([args] {
    if (args->help_meshlab) {
      std::cout << meshlab_parameter_table_markdown();
      return;
    }
    if (args->help_scenario) {
      std::cout << parameter_table_markdown();
      return;
    }
    run(*args);
  });
}

} // namespace sdflow::cli
