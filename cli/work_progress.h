#pragma once
//! \file work_progress.h
//! \brief Progress of a verb's long work on stderr, as `sdflow run` reports its steps: on a
//! terminal one line rewritten every second (the verb, the stage, its seconds so far) once a stage
//! has lasted a second; otherwise a line when a stage has lasted 2 s, then every 10 s. Nothing
//! under `-q` (the log level above info), nothing for work that ends within a second.

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <stop_token>
#include <string>
#include <thread>

namespace sdflow::cli {

class WorkProgress {
public:
  //! `verb` begins each line ("render: gnuplot drawing 285422 triangles: 3 s").
  explicit WorkProgress(std::string verb);
  //! Clears the terminal's progress line.
  ~WorkProgress();
  WorkProgress(const WorkProgress&) = delete;
  WorkProgress& operator=(const WorkProgress&) = delete;

  //! The work now under way, replacing the previous stage.
  void stage(std::string what);
  //! The work is over: the line is cleared before the verb prints its result.
  void finish();

private:
  using Clock = std::chrono::steady_clock;
  //! The ticker thread: wakes every second until stopped and shows the stage.
  void tick(std::stop_token stop);
  //! Draw the terminal line, or print a plain line when one is due (the mutex held).
  void show(Clock::time_point now);

  std::string verb_;
  bool enabled_ = false, tty_ = false;
  std::mutex mutex_;
  std::condition_variable_any wake_;
  std::string stage_;
  Clock::time_point stage_start_, last_line_;
  bool line_open_ = false; //!< a terminal line is showing
  std::jthread ticker_;    //!< last: stopped and joined first
};

} // namespace sdflow::cli
