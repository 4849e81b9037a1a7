#include "sdflow/run/run_lock.h"

#include "sdflow/errors.h"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <string>
#include <sys/file.h>
#include <unistd.h>

namespace sdflow {

RunLock::RunLock(const std::filesystem::path& dir)
{
  const std::filesystem::path file = dir / file_name;
  fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0)
    throw IoError(fmt::format("{}: cannot create the run's lock file ({})", file.string(), std::strerror(errno)));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    char buffer[32] = {};
    const ssize_t n = ::pread(fd_, buffer, sizeof buffer - 1, 0);
    ::close(fd_);
    fd_ = -1;
    std::string holder(buffer, n > 0 ? static_cast<std::size_t>(n) : 0);
    while (!holder.empty() && (holder.back() == '\n' || holder.back() == ' '))
      holder.pop_back();
    if (error == EWOULDBLOCK)
      throw InvalidParameter(fmt::format("{} is in use by another sdflow run (process {}, lock {}): wait for it to "
                                         "end, stop it, or choose another directory",
                                         dir.string(), holder.empty() ? "unknown" : holder, file.string()));
    throw IoError(fmt::format("{}: cannot lock the run directory ({})", file.string(), std::strerror(error)));
  }
  const std::string pid = fmt::format("{}\n", ::getpid());
  if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size())) {
    // The PID only informs whoever is refused; the lock itself holds.
  }
}

RunLock::~RunLock()
{
  if (fd_ >= 0)
    ::close(fd_); // releases the lock; the file stays (removing it would race with a new locker)
}

} // namespace sdflow
