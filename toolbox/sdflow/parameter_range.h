#pragma once
//! \file parameter_range.h
//! \brief The allowed values of a numeric parameter, stated once where the option is defined and
//! read by every check and every table that shows it: the run schema (run/parameter_schema.h) and
//! the option checks of the stages it configures (retri/pipeline.h's RetriangulationRanges).

#include <limits>
#include <string>
#include <string_view>

namespace sdflow {

//! The allowed values of a number: min and max, each end open or closed; infinite values only
//! where `infinite_allowed` (a limit that may be "none"); NaN never.
struct ParameterRange {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_open = false;
  bool max_open = false;
  bool infinite_allowed = false;

  bool contains(double value) const;
  //! "≥ 0", "> 0", "in [0, 60]", "in (0, 1]"; "" when any number is allowed.
  std::string text() const;
};

//! Throws InvalidParameter "NAME must be RANGE, got VALUE" (NAME: the scenario key) when `range`
//! does not contain `value`.
void check_in_range(const ParameterRange& range, double value, std::string_view name);

} // namespace sdflow
