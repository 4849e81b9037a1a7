#pragma once
//! \file expression.h
//! \brief A user formula f(x, y, z) as an implicit surface, parsed by muparser.

#include "sdflow/shapes/implicit.h"

#include <string>

namespace sdflow {

struct ExpressionParameters {
  //! muparser syntax in the variables x, y, z, e.g. "x^2 + y^2 + z^2 - 1" or
  //! "(sqrt(x^2 + y^2) - 2)^2 + z^2 - 0.5^2"; constants _pi and _e. Negative inside.
  std::string expression;
  Eigen::AlignedBox3d box; //!< where to look for f = 0 (non-empty, finite)
  //! Smallest thickness or gap the sampling grid must resolve; 0 = only the target edge length
  //! sets the grid.
  double feature_size = 0;
};

//! The surface f = 0 of a parsed formula; gradients by central differences. Throws
//! InvalidParameter naming the position and reason when the formula does not parse, or when the
//! box is empty or not finite.
ImplicitSurface expression_surface(const ExpressionParameters& parameters);

} // namespace sdflow
