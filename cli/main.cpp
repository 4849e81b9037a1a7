//! The `sdflow` command: surface diffusion flow and its toolbox from the shell.
//!
//! Exit codes: 0 success; 1 unexpected failure; 2 bad input (unreadable or invalid mesh, bad
//! parameter, command-line error, a path that cannot be used); 3 numerical failure (solver,
//! unstable run); 4 environment failure (disk or quota full, file size limit, read-only file
//! system); 130 / 143 a run stopped by SIGINT / SIGTERM after writing a checkpoint.

#include "exit_status.h"
#include "numbers.h"
#include "verbs.h"

#include "sdflow/errors.h"
#include "sdflow/log.h"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <new>

namespace {

void install_stderr_logger(bool verbose, bool quiet)
{
  auto sink = std::make_shared<spdlog::sinks::stderr_color_sink_mt>();
  auto logger = std::make_shared<spdlog::logger>("sdflow", sink);
  logger->set_pattern("%^%l%$: %v");
  logger->set_level(quiet ? spdlog::level::err : verbose ? spdlog::level::debug : spdlog::level::info);
  sdflow::set_logger(logger);
}

} // namespace

int main(int argc, char** argv)
{
  CLI::App app{"sdflow: surface diffusion flow (V_N = -ΔH) on triangulated surfaces"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "sdflow 0.1.0");
  bool verbose = false, quiet = false;
  app.add_flag("-v,--verbose", verbose, "Log debugging detail");
  app.add_flag("-q,--quiet", quiet, "Log errors only");
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
  sdflow::cli::require_plain_numbers(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  } catch (const sdflow::cli::ExitStatus& e) {
    return e.code;
  } catch (const sdflow::SolverFailure& e) {
    std::cerr << "sdflow: error: " << e.what() << '\n';
    return 3;
  } catch (const sdflow::EnvironmentFailure& e) {
    std::cerr << "sdflow: environment failure: " << e.what() << '\n';
    return 4;
  } catch (const sdflow::Error& e) {
    std::cerr << "sdflow: error: " << e.what() << '\n';
    return 2;
  } catch (const std::filesystem::filesystem_error& e) {
    // A path the request named cannot be used (permissions, a file where a directory should be).
    const int error = e.code().value();
    const bool environment = error == ENOSPC || error == EDQUOT || error == EFBIG || error == EROFS || error == EIO;
    std::cerr << "sdflow: " << (environment ? "environment failure: " : "error: ") << e.what() << '\n';
    return environment ? 4 : 2;
  } catch (const std::bad_alloc&) {
    std::cerr << "sdflow: out of memory (std::bad_alloc): the request needs more memory than this machine gives "
                 "it; try a coarser resolution\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "sdflow: unexpected error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
