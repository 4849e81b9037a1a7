//! libFuzzer harness: the τ schedule reader (flow/time_step.h, CSV first_step,last_step,tau) and
//! the lookups a run makes in what it read.
#include "fuzz_common.h"

#include "sdflow/flow/time_step.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  sdflow::fuzz::quiet();
  const auto file = sdflow::fuzz::scratch_file({reinterpret_cast<const char*>(data), size}, ".csv");
  try {
    const sdflow::TauSchedule schedule = sdflow::read_schedule(file);
    for (long step : {1L, 2L, 100L, 1000000L})
      (void)schedule.tau_for_step(step);
  } catch (const sdflow::Error&) {
  }
  return 0;
}
