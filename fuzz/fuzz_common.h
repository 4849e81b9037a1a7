#pragma once
//! \file fuzz_common.h
//! \brief What every harness shares: the reader's bytes through validation, with sdflow's own
//! exceptions (the documented way to refuse an input) caught and everything else left to crash.

#include "sdflow/errors.h"
#include "sdflow/io/detail/formats.h"
#include "sdflow/io/validate.h"
#include "sdflow/log.h"

#include <spdlog/sinks/null_sink.h>
#include <spdlog/spdlog.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string_view>
#include <unistd.h>

namespace sdflow::fuzz {

//! Silence the library's logger once (the fuzzer's own output is what matters).
inline void quiet()
{
  static const bool done = [] {
    set_logger(std::make_shared<spdlog::logger>("fuzz", std::make_shared<spdlog::sinks::null_sink_mt>()));
    return true;
  }();
  (void)done;
}

//! Parse `bytes` with `reader`, then validate and orient what it read. An sdflow::Error is a
//! refusal with a reason, which is fine; any other exception, a crash or a sanitizer report is a
//! finding.
template <class Reader>
int read_and_validate(const std::uint8_t* data, std::size_t size, Reader reader, MeshFormat format,
                      const char* name)
{
  quiet();
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    const PolygonSoup soup = reader(detail::without_byte_order_mark(bytes, format), name);
    BuildOptions options;
    options.merge_duplicate_vertices = format == MeshFormat::stl;
    (void)build_mesh(soup, name, options);
  } catch (const sdflow::Error&) {
  }
  return 0;
}

//! A file holding `bytes`, for the readers that take a path (one per process, rewritten per input).
inline std::filesystem::path scratch_file(std::string_view bytes, const char* extension)
{
  static const std::filesystem::path dir = [] {
    auto d = std::filesystem::temp_directory_path() / ("sdflow-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  const std::filesystem::path file = dir / (std::string("input") + extension);
  std::ofstream(file, std::ios::binary | std::ios::trunc).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return file;
}

} // namespace sdflow::fuzz
