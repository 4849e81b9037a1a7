#include "sdflow/log.h"

#include <OpenMesh/Core/System/omstream.hh>
#include <spdlog/sinks/null_sink.h>

#include <iostream>
#include <mutex>
#include <streambuf>
#include <string>

namespace sdflow {
namespace {

std::shared_ptr<spdlog::logger>& logger_slot()
{
  static std::shared_ptr<spdlog::logger> slot =
      std::make_shared<spdlog::logger>("sdflow", std::make_shared<spdlog::sinks::null_sink_mt>());
  return slot;
}

//! A stream buffer that hands each complete line to the logger at debug level, as "OpenMesh: ...".
class LinesToLogger : public std::streambuf {
protected:
  int overflow(int c) override
  {
    if (c == traits_type::eof())
      return traits_type::not_eof(c);
    const std::lock_guard lock(mutex_);
    if (c == '\n') {
      if (!line_.empty())
        logger().debug("OpenMesh: {}", line_);
      line_.clear();
    } else {
      line_.push_back(static_cast<char>(c));
    }
    return c;
  }

private:
  std::mutex mutex_;
  std::string line_;
};

//! OpenMesh writes what it refuses to its error stream, stderr by default ("PolyMeshT::add_face:
//! patch re-linking failed" when a rebuild tries a face its connectivity cannot take, which the
//! caller then handles). The library never prints (log.h): that stream goes to the logger instead.
void route_openmesh_messages()
{
  static std::once_flag once;
  std::call_once(once, [] {
    static LinesToLogger buffer;
    static std::ostream lines(&buffer);
    omerr().disconnect(std::cerr);
    omerr().connect(lines);
  });
}

} // namespace

spdlog::logger& logger()
{
  route_openmesh_messages();
  return *logger_slot();
}

void set_logger(std::shared_ptr<spdlog::logger> logger)
{
  route_openmesh_messages();
  if (logger)
    logger_slot() = std::move(logger);
}

} // namespace sdflow
