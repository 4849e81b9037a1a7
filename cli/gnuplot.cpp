#include "gnuplot.h"

#include "sdflow/errors.h"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <iterator>
#include <spawn.h>
#include <stdexcept>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace sdflow::cli {

namespace fs = std::filesystem;

namespace {

//! The text with control characters shown as \xNN, for the message that refuses it.
std::string printable(const std::string& text)
{
  std::string out;
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    out += u < 0x20 || u == 0x7f ? fmt::format("\\x{:02x}", u) : std::string(1, c);
  }
  return out;
}

} // namespace

std::string gnuplot_quoted(const std::string& text)
{
  // A newline ends gnuplot's command, and what follows would run as commands of its own (even
  // `system`); no control character has a place in a title, a label or a path drawn by gnuplot.
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c == 0x7f)
      throw InvalidParameter(fmt::format("'{}' holds a control character (byte 0x{:02x} at position {}), which "
                                         "gnuplot cannot take in a string; remove it",
                                         printable(text), c, i));
  }
  std::string out = "'";
  for (char c : text)
    out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

void run_gnuplot(const fs::path& script, const fs::path& log)
{
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  std::string program = "gnuplot", script_argument = script.string();
  char* argv[] = {program.data(), script_argument.data(), nullptr};
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0)
    throw std::runtime_error(fmt::format("cannot run gnuplot ({}); install it (Debian package gnuplot-nox)",
                                         std::strerror(spawned)));
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR)
      throw std::runtime_error(fmt::format("waiting for gnuplot failed ({})", std::strerror(errno)));
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::ifstream in(log, std::ios::binary);
    std::string message{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    while (!message.empty() && (message.back() == '\n' || message.back() == ' '))
      message.pop_back();
    const std::string how = WIFEXITED(status) ? fmt::format("exit status {}", WEXITSTATUS(status))
                                              : fmt::format("signal {}", WIFSIGNALED(status) ? WTERMSIG(status) : 0);
    throw std::runtime_error(fmt::format("gnuplot failed ({}){}{}", how, message.empty() ? "" : ":\n", message));
  }
}

} // namespace sdflow::cli
