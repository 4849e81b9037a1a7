#include "sdflow/solve/suitesparse_output.h"

#include "sdflow/log.h"

#include <SuiteSparse_config.h>

#include <algorithm>
#include <array>
#include <cstdarg>
#include <cstdio>
#include <mutex>
#include <string>

namespace sdflow {
namespace {

//! SuiteSparse's printf: a message arrives in pieces ("CHOLMOD warning:", " %s.", "\n"), so the
//! pieces are gathered per thread and logged a line at a time.
int log_suitesparse_text(const char* format, ...)
{
  thread_local std::string line;
  std::array<char, 1024> piece{};
  va_list arguments;
  va_start(arguments, format);
  const int length = std::vsnprintf(piece.data(), piece.size(), format, arguments);
  va_end(arguments);
  if (length < 0)
    return length;
  line.append(piece.data(), std::min<std::size_t>(static_cast<std::size_t>(length), piece.size() - 1));
  for (std::size_t end = line.find('\n'); end != std::string::npos; end = line.find('\n')) {
    if (end > 0)
      logger().debug("SuiteSparse: {}", line.substr(0, end));
    line.erase(0, end + 1);
  }
  return length;
}

} // namespace

void route_suitesparse_output()
{
  static std::once_flag once;
  std::call_once(once, [] { SuiteSparse_config.printf_func = &log_suitesparse_text; });
}

} // namespace sdflow
