//! libFuzzer harness: the scenario reader (run/parameters.h, TOML) and the validation of what it
//! read, as `sdflow run SCENARIO.toml` does before any work.
#include "fuzz_common.h"

#include "sdflow/run/parameters.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  sdflow::fuzz::quiet();
  const auto file = sdflow::fuzz::scratch_file({reinterpret_cast<const char*>(data), size}, ".toml");
  try {
    sdflow::RunParameters parameters;
    sdflow::read_run_parameters(file, parameters);
    sdflow::validate_run_parameters(parameters);
    (void)sdflow::run_parameters_toml(parameters);
  } catch (const sdflow::Error&) {
  }
  return 0;
}
