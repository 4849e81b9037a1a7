#pragma once
//! \file failure.h
//! \brief How a failed command ends: the message on stderr, and with `--json` one JSON object on
//! stdout, `{error, message, exit_code, findings}` (README, "Command line"), then the exit code:
//! 1 unexpected failure, 2 bad input, 3 numerical failure, 4 environment failure.

#include <CLI/CLI.hpp>

#include <exception>

namespace sdflow::cli {

//! Whether the verb that was parsed was given `--json`.
bool json_requested(const CLI::App& app);

//! Report the exception thrown by parsing or running a verb of `app`; returns the exit code.
int report_failure(CLI::App& app, std::exception_ptr failure);

} // namespace sdflow::cli
