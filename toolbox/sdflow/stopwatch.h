#pragma once
//! \file stopwatch.h
//! \brief Wall time since construction (std::chrono::steady_clock), for the per-stage timings of
//! runs (timings.csv, simulation.h) and of the re-triangulation pipeline, and the process's CPU time.

#include <chrono>
#include <ctime>

namespace sdflow {

class Stopwatch {
public:
  //! Seconds since construction or the last restart().
  double seconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
  //! The seconds so far; counting starts again.
  double restart()
  {
    const auto now = Clock::now();
    const double s = std::chrono::duration<double>(now - start_).count();
    start_ = now;
    return s;
  }

private:
  using Clock = std::chrono::steady_clock;
  Clock::time_point start_ = Clock::now();
};

//! CPU seconds the process has used so far, all threads together (std::clock): beside wall time,
//! what a step costs on a machine other programs load too.
inline double process_cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

} // namespace sdflow
