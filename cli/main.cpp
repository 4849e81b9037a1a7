//! The `sdflow` command: surface diffusion flow and its toolbox from the shell.
//!
//! Exit codes: 0 success; 1 unexpected failure; 2 bad input (unreadable or invalid mesh, bad
//! parameter, command-line error, a path that cannot be used); 3 numerical failure (solver,
//! unstable run); 4 environment failure (disk or quota full, file size limit, read-only file
//! system); 130 / 143 a run stopped by SIGINT / SIGTERM after writing a checkpoint.

#include "failure.h"
#include "help_formatter.h"
#include "numbers.h"
#include "common_options.h"
#include "verbs.h"

#include "sdflow/log.h"
#include "sdflow/version.h"

#include <fmt/format.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <cstdio>
#include <exception>
#include <memory>
#include <unistd.h>

namespace {

void install_stderr_logger(bool verbose, bool quiet)
{
  auto sink = std::make_shared<spdlog::sinks::stderr_color_sink_mt>();
  auto logger = std::make_shared<spdlog::logger>("sdflow", sink);
  // On a terminal a log line first clears the progress line it may interrupt (run's bar,
  // WorkProgress); the progress is drawn again on its next tick.
  logger->set_pattern(::isatty(::fileno(stderr)) ? "\r\033[K%^%l%$: %v" : "%^%l%$: %v");
  logger->set_level(quiet ? spdlog::level::err : verbose ? spdlog::level::debug : spdlog::level::info);
  sdflow::set_logger(logger);
}

} // namespace

int main(int argc, char** argv)
{
  CLI::App app{"sdflow: surface diffusion flow (V_N = -ΔH) on triangulated surfaces"};
  app.formatter(std::make_shared<sdflow::cli::HelpFormatter>());
  app.require_subcommand(1);
  app.set_version_flag("--version", fmt::format("sdflow {} (commit {})", sdflow::version(), sdflow::git_commit()));
  bool verbose = false, quiet = false;
  app.add_flag("-v,--verbose", verbose, "Log debugging detail");
  app.add_flag("-q,--quiet", quiet, "Log errors only, no progress");
  app.parse_complete_callback([&] { install_stderr_logger(verbose, quiet); });

  sdflow::cli::add_fill_holes_verb(app);
  sdflow::cli::add_normals_verb(app);
  sdflow::cli::add_plot_verb(app);
  sdflow::cli::add_reconstruct_verb(app);
  sdflow::cli::add_remesh_verb(app);
  sdflow::cli::add_render_verb(app);
  sdflow::cli::add_retriangulate_verb(app);
  sdflow::cli::add_run_verb(app);
  sdflow::cli::add_shape_verb(app);
  sdflow::cli::add_stats_verb(app);
  sdflow::cli::add_repair_verb(app);
  sdflow::cli::add_intersections_verb(app);
  sdflow::cli::add_components_verb(app);
  sdflow::cli::add_union_verb(app);
  sdflow::cli::add_axisymmetric_verb(app);
  for (CLI::App* verb : app.get_subcommands([](CLI::App*) { return true; }))
    sdflow::cli::add_verbosity_flags(*verb, verbose, quiet);
  sdflow::cli::require_plain_numbers(app);

  try {
    app.parse(argc, argv);
  } catch (...) {
    return sdflow::cli::report_failure(app, std::current_exception(), sdflow::cli::json_in_arguments(argc, argv));
  }
  return 0;
}
