//! libFuzzer harness: the VTK XML PolyData reader (io/vtp.cpp), then validation (io/validate.h).
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  return sdflow::fuzz::read_and_validate(data, size, sdflow::detail::read_vtp, sdflow::MeshFormat::vtp, "fuzz.vtp");
}
