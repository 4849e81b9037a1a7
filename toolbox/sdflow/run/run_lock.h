#pragma once
//! \file run_lock.h
//! \brief One process at a time in a run directory: `DIR/run.lock`, locked with flock(2) for as
//! long as the process works there and holding its PID. The kernel drops the lock when the process
//! dies however it dies, so a lock file left by a killed run never blocks the next one.

#include <filesystem>

namespace sdflow {

class RunLock {
public:
  //! Lock `dir` (which must exist). Throws InvalidParameter naming the PID of the process that
  //! holds the lock, IoError when the lock file cannot be created.
  explicit RunLock(const std::filesystem::path& dir);
  ~RunLock();
  RunLock(const RunLock&) = delete;
  RunLock& operator=(const RunLock&) = delete;

  //! The lock file's name inside a run directory.
  static constexpr const char* file_name = "run.lock";

private:
  int fd_ = -1;
};

} // namespace sdflow
