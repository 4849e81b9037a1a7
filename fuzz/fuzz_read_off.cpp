//! libFuzzer harness: the OFF reader (io/off.cpp), then validation (io/validate.h).
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  return sdflow::fuzz::read_and_validate(data, size, sdflow::detail::read_off, sdflow::MeshFormat::off, "fuzz.off");
}
