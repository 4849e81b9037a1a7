#include "sdflow/shapes/expression.h"

#include "sdflow/errors.h"

#include <fmt/format.h>
#include <muParser.h>

#include <cmath>
#include <memory>

namespace sdflow {
namespace {

//! A parser bound to its own variables: muparser keeps pointers to them, so they live together.
struct BoundExpression {
  mu::Parser parser;
  double x = 0, y = 0, z = 0;

  explicit BoundExpression(const std::string& expression)
  {
    parser.DefineVar("x", &x);
    parser.DefineVar("y", &y);
    parser.DefineVar("z", &z);
    parser.SetExpr(expression);
  }

  double operator()(const Eigen::Vector3d& p)
  {
    x = p.x();
    y = p.y();
    z = p.z();
    return parser.Eval();
  }
};

} // namespace

ImplicitSurface expression_surface(const ExpressionParameters& parameters)
{
  const auto& box = parameters.box;
  if (!box.min().allFinite() || !box.max().allFinite() || !(box.min().array() < box.max().array()).all())
    throw InvalidParameter(fmt::format("expression: the box [{}, {}, {}] to [{}, {}, {}] must be finite with min < max "
                                       "on every axis",
                                       box.min().x(), box.min().y(), box.min().z(), box.max().x(), box.max().y(),
                                       box.max().z()));
  if (!(parameters.feature_size >= 0))
    throw InvalidParameter(fmt::format("expression: feature size {} must not be negative", parameters.feature_size));
  std::shared_ptr<BoundExpression> bound;
  try {
    bound = std::make_shared<BoundExpression>(parameters.expression);
    (*bound)(box.center()); // muparser parses on first evaluation: surface syntax errors here
    int results = 0;
    bound->parser.Eval(results);
    if (results != 1)
      throw InvalidParameter(fmt::format("expression '{}' gives {} values; it must give one, f(x, y, z)",
                                         parameters.expression, results));
  } catch (const mu::Parser::exception_type& e) {
    throw InvalidParameter(fmt::format("expression '{}' does not parse: {} (at position {})", parameters.expression,
                                       e.GetMsg(), e.GetPos()));
  }
  ImplicitSurface s;
  s.name = "expression";
  s.value = [bound](const Eigen::Vector3d& p) {
    try {
      return (*bound)(p);
    } catch (const mu::Parser::exception_type&) {
      return std::nan(""); // evaluation errors (not parse errors) read as "undefined here"
    }
  };
  s.box = box;
  s.feature_size = parameters.feature_size;
  return s;
}

} // namespace sdflow
