#include "work_progress.h"

#include "sdflow/log.h"

#include <fmt/format.h>

#include <cstdio>
#include <iostream>
#include <unistd.h>

namespace sdflow::cli {
namespace {

constexpr auto terminal_delay = std::chrono::seconds(1);
constexpr auto first_line_delay = std::chrono::seconds(2);
constexpr auto line_interval = std::chrono::seconds(10);

} // namespace

WorkProgress::WorkProgress(std::string verb)
    : verb_(std::move(verb)), enabled_(logger().should_log(spdlog::level::info)),
      tty_(::isatty(::fileno(stderr)) != 0)
{
  if (enabled_)
    ticker_ = std::jthread([this](std::stop_token stop) { tick(stop); });
}

WorkProgress::~WorkProgress() { finish(); }

void WorkProgress::stage(std::string what)
{
  std::lock_guard lock(mutex_);
  stage_ = std::move(what);
  stage_start_ = Clock::now();
  // The first line after first_line_delay, the next ones every line_interval.
  last_line_ = stage_start_ - line_interval + first_line_delay;
}

void WorkProgress::finish()
{
  if (ticker_.joinable()) {
    ticker_.request_stop();
    wake_.notify_all();
    ticker_.join();
  }
  std::lock_guard lock(mutex_);
  if (line_open_)
    std::cerr << "\r\033[K" << std::flush;
  line_open_ = false;
}

void WorkProgress::show(Clock::time_point now)
{
  if (stage_.empty())
    return;
  const auto elapsed = now - stage_start_;
  const long seconds = std::chrono::duration_cast<std::chrono::seconds>(elapsed).count();
  const std::string text = fmt::format("{}: {}: {} s", verb_, stage_, seconds);
  if (tty_) {
    if (elapsed < terminal_delay)
      return;
    std::cerr << '\r' << text << "\033[K" << std::flush;
    line_open_ = true;
  } else if (now - last_line_ >= line_interval) {
    std::cerr << text << '\n' << std::flush;
    last_line_ = now;
  }
}

void WorkProgress::tick(std::stop_token stop)
{
  std::unique_lock lock(mutex_);
  while (!stop.stop_requested()) {
    wake_.wait_for(lock, stop, std::chrono::seconds(1), [] { return false; });
    if (!stop.stop_requested())
      show(Clock::now());
  }
}

} // namespace sdflow::cli
