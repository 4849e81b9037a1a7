#include "failure.h"

#include "exit_status.h"
#include "json_report.h"

#include "sdflow/errors.h"
#include "sdflow/io/validate.h"

#include <cerrno>
#include <filesystem>
#include <iostream>
#include <new>
#include <string>
#include <string_view>
#include <vector>

namespace sdflow::cli {
namespace {

//! What went wrong, for stderr and for JSON.
struct Failure {
  int exit_code = 1;
  std::string kind;    //!< JSON `error`: usage, invalid-mesh, io-error, invalid-parameter, ...
  std::string prefix;  //!< stderr's "sdflow: error: " or "sdflow: environment failure: "
  std::string message;
  std::vector<Finding> findings;
};

Failure classify(std::exception_ptr failure)
{
  try {
    std::rethrow_exception(failure);
  } catch (const SolverFailure& e) {
    return {3, "numerical-failure", "sdflow: error: ", e.what(), {}};
  } catch (const EnvironmentFailure& e) {
    return {4, "environment-failure", "sdflow: environment failure: ", e.what(), {}};
  } catch (const MeshValidationError& e) {
    return {2, "invalid-mesh", "sdflow: error: ", e.what(), e.findings()};
  } catch (const InvalidMesh& e) {
    return {2, "invalid-mesh", "sdflow: error: ", e.what(), {}};
  } catch (const InvalidParameter& e) {
    return {2, "invalid-parameter", "sdflow: error: ", e.what(), {}};
  } catch (const IoError& e) {
    return {2, "io-error", "sdflow: error: ", e.what(), {}};
  } catch (const Error& e) {
    return {2, "error", "sdflow: error: ", e.what(), {}};
  } catch (const std::filesystem::filesystem_error& e) {
    // A path the request named cannot be used (permissions, a file where a directory should be).
    const int error = e.code().value();
    if (error == ENOSPC || error == EDQUOT || error == EFBIG || error == EROFS || error == EIO)
      return {4, "environment-failure", "sdflow: environment failure: ", e.what(), {}};
    return {2, "io-error", "sdflow: error: ", e.what(), {}};
  } catch (const std::bad_alloc&) {
    return {1, "out-of-memory", "sdflow: ",
            "out of memory (std::bad_alloc): the request needs more memory than this machine gives it; try a "
            "coarser resolution",
            {}};
  } catch (const std::exception& e) {
    return {1, "internal-error", "sdflow: unexpected error: ", e.what(), {}};
  }
}

void print_failure_json(const Failure& f)
{
  print_json(toml::table{{"error", f.kind},
                         {"message", f.message},
                         {"exit_code", f.exit_code},
                         {"findings", findings_json(f.findings)}});
}

} // namespace

bool json_requested(const CLI::App& app)
{
  for (const CLI::App* verb : app.get_subcommands())
    if (const CLI::Option* json = verb->get_option_no_throw("--json"); json && json->count() > 0)
      return true;
  return false;
}

bool json_in_arguments(int argc, const char* const* argv)
{
  for (int i = 1; i < argc; ++i) {
    const std::string_view argument = argv[i];
    if (argument == "--")
      return false;
    if (argument == "--json")
      return true;
  }
  return false;
}

int report_failure(CLI::App& app, std::exception_ptr failure, bool json_asked)
{
  try {
    std::rethrow_exception(failure);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e) == 0 ? 0 : 2;
    if (code != 0 && (json_requested(app) || json_asked))
      print_failure_json({code, "usage", "", e.what(), {}});
    return code;
  } catch (const ExitStatus& e) {
    return e.code; // the verb has reported
  } catch (...) {
  }
  const Failure f = classify(failure);
  std::cerr << f.prefix << f.message << '\n';
  if (json_requested(app))
    print_failure_json(f);
  return f.exit_code;
}

} // namespace sdflow::cli
