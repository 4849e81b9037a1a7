//! libFuzzer harness: the validator (io/validate.h) on soups no reader would produce. The bytes are
//! decoded as: one byte of point count, one of flags (merge duplicates, orient), then points as
//! three small signed integers (a coarse grid makes coincident, collinear and coplanar corners
//! common) or, when the flag asks, raw doubles, and the rest as polygons: a length byte and indices.
#include "fuzz_common.h"

#include <cstring>
#include <limits>

namespace {

class Bytes {
public:
  Bytes(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  bool empty() const { return at_ >= size_; }
  std::uint8_t byte() { return at_ < size_ ? data_[at_++] : 0; }
  double real()
  {
    double value = 0;
    if (size_ - std::min(at_, size_) >= sizeof value) {
      std::memcpy(&value, data_ + at_, sizeof value);
      at_ += sizeof value;
    } else {
      at_ = size_;
    }
    return value;
  }

private:
  const std::uint8_t* data_;
  std::size_t size_, at_ = 0;
};

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  sdflow::fuzz::quiet();
  Bytes in(data, size);
  const int points = in.byte() % 64;
  const std::uint8_t flags = in.byte();
  sdflow::PolygonSoup soup;
  for (int i = 0; i < points; ++i) {
    Eigen::Vector3d p;
    for (int k = 0; k < 3; ++k)
      p[k] = (flags & 4) ? in.real() : static_cast<double>(static_cast<std::int8_t>(in.byte()) % 5);
    soup.points.push_back(p);
  }
  while (!in.empty()) {
    const int length = 3 + in.byte() % 4;
    std::vector<long long> polygon;
    for (int k = 0; k < length; ++k) {
      const std::uint8_t index = in.byte();
      polygon.push_back(index == 255 ? -1 : index % std::max(points + 2, 1));
    }
    soup.polygons.push_back(std::move(polygon));
  }
  sdflow::BuildOptions options;
  options.merge_duplicate_vertices = flags & 1;
  options.orient_outward = !(flags & 2);
  try {
    (void)sdflow::build_mesh(soup, "fuzz", options);
  } catch (const sdflow::Error&) {
  }
  return 0;
}
