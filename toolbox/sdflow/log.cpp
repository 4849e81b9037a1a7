#include "sdflow/log.h"

#include <spdlog/sinks/null_sink.h>

namespace sdflow {
namespace {

std::shared_ptr<spdlog::logger>& logger_slot()
{
  static std::shared_ptr<spdlog::logger> slot =
      std::make_shared<spdlog::logger>("sdflow", std::make_shared<spdlog::sinks::null_sink_mt>());
  return slot;
}

} // namespace

spdlog::logger& logger() { return *logger_slot(); }

void set_logger(std::shared_ptr<spdlog::logger> logger)
{
  if (logger)
    logger_slot() = std::move(logger);
}

} // namespace sdflow
