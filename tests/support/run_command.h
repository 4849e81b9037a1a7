#pragma once
//! \file run_command.h
//! \brief Run the sdflow command line in tests and capture what it printed.

#include <array>
#include <csignal>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace sdflow::analytic {

struct CommandResult {
  int exit_code = -1;
  std::string output; //!< stdout and stderr, interleaved
};

//! Run `sdflow ARGUMENTS` (the binary built alongside the tests) through the shell.
inline CommandResult run_sdflow(const std::string& arguments)
{
  // Appended piece by piece: GCC 12 warns (-Warray-bounds, falsely) on a chain of operator+ here.
  std::string command = SDFLOW_CLI_PATH;
  command.append(" ").append(arguments).append(" 2>&1");
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

//! The lines of a text file (0 for a file that is not there yet).
inline long count_lines(const std::string& file)
{
  std::ifstream in(file);
  long n = 0;
  for (std::string line; std::getline(in, line);)
    ++n;
  return n;
}

//! `sdflow ARGUMENTS` started in the background, its output going to `log`; `file_limit` > 0
//! caps the size of every file it writes (RLIMIT_FSIZE), as a full disk would.
inline pid_t start_sdflow(const std::string& arguments, const std::string& log, rlim_t file_limit = 0)
{
  const pid_t child = fork();
  if (child == 0) {
    if (file_limit > 0) {
      signal(SIGXFSZ, SIG_IGN); // write() then fails with EFBIG, as it fails with ENOSPC on a full disk
      const rlimit limit{file_limit, file_limit};
      setrlimit(RLIMIT_FSIZE, &limit);
    }
    const std::string command = std::string(SDFLOW_CLI_PATH) + " " + arguments + " > " + log + " 2>&1";
    execl("/bin/sh", "sh", "-c", ("exec " + command).c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return child;
}

//! The exit code of a child (128 + the signal that ended it), once it has ended.
inline int wait_exit_code(pid_t child)
{
  int status = 0;
  waitpid(child, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

//! Poll `ready` every 2 ms while `child` runs. True once it holds with the child still running (to
//! be signalled); false when the child ended first, its exit code then in `exit_code`. No wall-clock
//! limit: a child that hangs is ended by ctest's timeout, not by a guess at how slow a machine is.
template <class Ready>
bool wait_while_running(pid_t child, Ready ready, int& exit_code)
{
  for (;;) {
    if (ready())
      return true;
    int status = 0;
    if (waitpid(child, &status, WNOHANG) == child) {
      exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      return false;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

} // namespace sdflow::analytic
