//! libFuzzer harness: the PLY reader (io/ply.cpp), then validation (io/validate.h).
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  return sdflow::fuzz::read_and_validate(data, size, sdflow::detail::read_ply, sdflow::MeshFormat::ply, "fuzz.ply");
}
