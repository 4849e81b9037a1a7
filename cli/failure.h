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

//! Whether the command line `arguments` asks for `--json` anywhere before a `--`: a command-line
//! error (no verb, an unknown verb) is reported as JSON too, though no verb parsed the flag.
bool json_in_arguments(int argc, const char* const* argv);

//! Report the exception thrown by parsing or running a verb of `app`; returns the exit code.
//! `json_asked` (json_in_arguments) reports a command-line error as JSON when no verb parsed `--json`.
int report_failure(CLI::App& app, std::exception_ptr failure, bool json_asked = false);

} // namespace sdflow::cli
