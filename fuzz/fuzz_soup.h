#pragma once
//! \file fuzz_soup.h
//! \brief The polygon soups of the validator's and the repair's harnesses, decoded from the fuzzer's
//! bytes: one byte of point count, one of flags (bit 2: raw doubles; the others are the harness's),
//! then points as three small signed integers (a coarse grid makes coincident, collinear and
//! coplanar corners common) or, when the flag asks, raw doubles, and the rest as polygons: a
//! length byte (3 to 6 corners) and indices (255 is -1; the others wrap a little past the points).

#include "sdflow/io/soup.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace sdflow::fuzz {

//! The fuzzer's bytes, read front to back; past the end every read gives 0.
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

//! A soup and the flags byte it was decoded with.
struct DecodedSoup {
  PolygonSoup soup;
  std::uint8_t flags = 0;
};

//! The soup the bytes describe (format above).
inline DecodedSoup decode_soup(const std::uint8_t* data, std::size_t size)
{
  Bytes in(data, size);
  const int points = in.byte() % 64;
  DecodedSoup out;
  out.flags = in.byte();
  for (int i = 0; i < points; ++i) {
    Eigen::Vector3d p;
    for (int k = 0; k < 3; ++k)
      p[k] = (out.flags & 4) ? in.real() : static_cast<double>(static_cast<std::int8_t>(in.byte()) % 5);
    out.soup.points.push_back(p);
  }
  while (!in.empty()) {
    const int length = 3 + in.byte() % 4;
    std::vector<long long> polygon;
    for (int k = 0; k < length; ++k) {
      const std::uint8_t index = in.byte();
      polygon.push_back(index == 255 ? -1 : index % std::max(points + 2, 1));
    }
    out.soup.polygons.push_back(std::move(polygon));
  }
  return out;
}

} // namespace sdflow::fuzz
