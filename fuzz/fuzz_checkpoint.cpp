//! libFuzzer harness: the checkpoint reader (run/checkpoint.h) that `run --resume` trusts.
#include "fuzz_common.h"

#include "sdflow/run/checkpoint.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  sdflow::fuzz::quiet();
  const auto file = sdflow::fuzz::scratch_file({reinterpret_cast<const char*>(data), size}, ".bin");
  try {
    (void)sdflow::read_checkpoint(file);
  } catch (const sdflow::Error&) {
  }
  return 0;
}
