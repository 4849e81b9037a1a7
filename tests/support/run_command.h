#pragma once
//! \file run_command.h
//! \brief Run the sdflow command line in tests and capture what it printed.

#include <array>
#include <cstdio>
#include <string>
#include <sys/wait.h>

namespace sdflow::analytic {

struct CommandResult {
  int exit_code = -1;
  std::string output; //!< stdout and stderr, interleaved
};

//! Run `sdflow ARGUMENTS` (the binary built alongside the tests) through the shell.
inline CommandResult run_sdflow(const std::string& arguments)
{
  const std::string command = std::string(SDFLOW_CLI_PATH) + " " + arguments + " 2>&1";
  CommandResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe)
    return result;
  std::array<char, 4096> buffer{};
  while (fgets(buffer.data(), buffer.size(), pipe))
    result.output += buffer.data();
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

} // namespace sdflow::analytic
