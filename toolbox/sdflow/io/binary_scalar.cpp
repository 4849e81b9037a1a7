//! The numeric types of binary mesh data, shared by the PLY and VTK XML readers (detail/formats.h).
#include "sdflow/io/detail/formats.h"

#include <cstdint>

namespace sdflow::detail {

std::size_t size_of(Scalar s)
{
  switch (s) {
  case Scalar::int8:
  case Scalar::uint8: return 1;
  case Scalar::int16:
  case Scalar::uint16: return 2;
  case Scalar::int32:
  case Scalar::uint32:
  case Scalar::float32: return 4;
  case Scalar::int64:
  case Scalar::uint64:
  case Scalar::float64: return 8;
  }
  return 1;
}

bool is_integer(Scalar s) { return s != Scalar::float32 && s != Scalar::float64; }

double load_as_double(const char* p, Scalar type, std::endian order)
{
  switch (type) {
  case Scalar::int8: return load_scalar<std::int8_t>(p, order);
  case Scalar::uint8: return load_scalar<std::uint8_t>(p, order);
  case Scalar::int16: return load_scalar<std::int16_t>(p, order);
  case Scalar::uint16: return load_scalar<std::uint16_t>(p, order);
  case Scalar::int32: return load_scalar<std::int32_t>(p, order);
  case Scalar::uint32: return load_scalar<std::uint32_t>(p, order);
  case Scalar::int64: return static_cast<double>(load_scalar<std::int64_t>(p, order));
  case Scalar::uint64: return static_cast<double>(load_scalar<std::uint64_t>(p, order));
  case Scalar::float32: return load_scalar<float>(p, order);
  case Scalar::float64: return load_scalar<double>(p, order);
  }
  return 0;
}

} // namespace sdflow::detail
