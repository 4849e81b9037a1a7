#include "sdflow/solve/blas_threads.h"

#include "sdflow/errors.h"

#include <fmt/format.h>

#include <dlfcn.h>

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <optional>
#include <string_view>
#include <thread>

namespace sdflow {
namespace {

//! A positive thread count from the environment variable `name`; nullopt when unset or empty.
std::optional<int> thread_count_from_environment(const char* name)
{
  const char* text = std::getenv(name);
  if (text == nullptr || *text == '\0')
    return std::nullopt;
  const std::string_view s(text);
  int n = 0;
  const auto [end, error] = std::from_chars(s.data(), s.data() + s.size(), n);
  if (error != std::errc() || end != s.data() + s.size() || n < 1)
    throw InvalidParameter(fmt::format("environment variable {}={}: expected a positive whole number of threads",
                                       name, s));
  return n;
}

//! The environment's word on BLAS threads, read once: a fixed count and a cap.
struct EnvironmentThreads {
  std::optional<int> fixed; //!< SDFLOW_BLAS_THREADS
  int cap = 0;              //!< OPENBLAS_NUM_THREADS, else OMP_NUM_THREADS, else the hardware threads
};

EnvironmentThreads read_environment()
{
  EnvironmentThreads e;
  e.fixed = thread_count_from_environment("SDFLOW_BLAS_THREADS");
  std::optional<int> cap = thread_count_from_environment("OPENBLAS_NUM_THREADS");
  if (!cap)
    cap = thread_count_from_environment("OMP_NUM_THREADS");
  e.cap = cap.value_or(static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
  return e;
}

} // namespace

int blas_threads_for(long unknowns, const BlasThreadPolicy& policy)
{
  static const EnvironmentThreads environment = read_environment();
  if (environment.fixed)
    return *environment.fixed;
  return unknowns < policy.single_thread_below ? 1 : environment.cap;
}

bool set_factorisation_threads(int threads)
{
  using SetInt = void (*)(int);
  // Looked up in the process's global symbols: OpenBLAS is loaded there as CHOLMOD's BLAS, and
  // libgomp as CHOLMOD's OpenMP runtime.
  static const auto set_blas = reinterpret_cast<SetInt>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
  static const auto set_levels = reinterpret_cast<SetInt>(dlsym(RTLD_DEFAULT, "omp_set_max_active_levels"));
  static const auto set_dynamic = reinterpret_cast<SetInt>(dlsym(RTLD_DEFAULT, "omp_set_dynamic"));
  threads = std::max(1, threads);
  // CHOLMOD's OpenMP loops ask for a fixed team of CHOLMOD_OMP_NUM_THREADS (4 in Debian's build),
  // which no thread-count call overrides: with one thread, no region may be active (level 0), so
  // each runs on the calling thread; with more, the runtime may shrink the team to the free cores.
  if (set_levels != nullptr && set_dynamic != nullptr) {
    set_levels(threads > 1 ? 1 : 0);
    set_dynamic(threads > 1 ? 1 : 0);
  }
  if (set_blas == nullptr)
    return false;
  set_blas(threads);
  return true;
}

} // namespace sdflow
