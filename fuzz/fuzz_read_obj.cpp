//! libFuzzer harness: the OBJ reader (io_obj.cpp), then validation (validate.h).
#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  return sdflow::fuzz::read_and_validate(data, size, sdflow::detail::read_obj, sdflow::MeshFormat::obj, "fuzz.obj");
}
