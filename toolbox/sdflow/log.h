#pragma once
//! \file log.h
//! \brief The library's logger. sdflow never prints: it logs to the "sdflow" spdlog logger, whose
//! sinks belong to the application (the CLI prints to stderr, the MeshLab plugin to its log).
//! OpenMesh's error stream goes to it too, at debug level.

#include <memory>
#include <spdlog/logger.h>

namespace sdflow {

//! The logger every toolbox function reports through. By default it has no sinks (silent).
spdlog::logger& logger();

//! Replace the logger's sinks and level; the CLI and the MeshLab plugin call this once.
void set_logger(std::shared_ptr<spdlog::logger> logger);

} // namespace sdflow
