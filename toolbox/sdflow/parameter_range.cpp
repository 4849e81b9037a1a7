#include "sdflow/parameter_range.h"

#include "sdflow/errors.h"

#include <fmt/format.h>

#include <cmath>

namespace sdflow {
namespace {

std::string number_text(double v)
{
  if (std::isinf(v))
    return v > 0 ? "∞" : "−∞";
  return fmt::format("{}", v);
}

} // namespace

bool ParameterRange::contains(double v) const
{
  if (std::isnan(v) || (std::isinf(v) && !infinite_allowed))
    return false;
  const bool above_min = min_open ? v > min : v >= min;
  const bool below_max = max_open ? v < max : v <= max;
  return above_min && below_max;
}

std::string ParameterRange::text() const
{
  const bool has_min = std::isfinite(min), has_max = std::isfinite(max);
  if (has_min && has_max)
    return fmt::format("in {}{}, {}{}", min_open ? '(' : '[', number_text(min), number_text(max), max_open ? ')' : ']');
  if (has_min)
    return fmt::format("{} {}", min_open ? ">" : "≥", number_text(min));
  if (has_max)
    return fmt::format("{} {}", max_open ? "<" : "≤", number_text(max));
  return "";
}

void check_in_range(const ParameterRange& range, double value, std::string_view name)
{
  if (!range.contains(value))
    throw InvalidParameter(fmt::format("{} must be {}{}, got {}", name, std::isinf(value) ? "finite and " : "",
                                       range.text(), value));
}

} // namespace sdflow
