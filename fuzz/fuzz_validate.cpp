//! libFuzzer harness: the validator (io/validate.h) on soups no reader would produce (fuzz_soup.h);
//! flag bit 0 merges duplicate vertices, bit 1 leaves the orientation alone.
#include "fuzz_common.h"
#include "fuzz_soup.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  sdflow::fuzz::quiet();
  const auto [soup, flags] = sdflow::fuzz::decode_soup(data, size);
  sdflow::BuildOptions options;
  options.merge_duplicate_vertices = flags & 1;
  options.orient_outward = !(flags & 2);
  try {
    (void)sdflow::build_mesh(soup, "fuzz", options);
  } catch (const sdflow::Error&) {
  }
  return 0;
}
