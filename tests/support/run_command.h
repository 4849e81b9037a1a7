#pragma once
//! \file run_command.h
//! \brief Run the sdflow command line in tests and capture what it printed.

#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

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

struct SeparateStreams {
  int exit_code = -1;
  std::string out; //!< stdout
  std::string err; //!< stderr
};

//! Run `sdflow ARGUMENTS` through the shell and capture stdout and stderr apart.
inline SeparateStreams run_sdflow_streams(const std::string& arguments)
{
  char err_file[] = "/tmp/sdflow_stderr_XXXXXX";
  const int fd = ::mkstemp(err_file);
  SeparateStreams result;
  if (fd < 0)
    return result;
  ::close(fd);
  const std::string command = std::string(SDFLOW_CLI_PATH) + " " + arguments + " 2>" + err_file;
  if (FILE* pipe = popen(command.c_str(), "r")) {
    std::array<char, 4096> buffer{};
    std::size_t n = 0;
    while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
      result.out.append(buffer.data(), n);
    const int status = pclose(pipe);
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  std::ifstream err(err_file, std::ios::binary);
  result.err.assign(std::istreambuf_iterator<char>(err), std::istreambuf_iterator<char>());
  std::remove(err_file);
  return result;
}

} // namespace sdflow::analytic
