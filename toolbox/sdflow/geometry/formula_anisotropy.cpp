#include "sdflow/geometry/formula_anisotropy.h"

#include "sdflow/errors.h"

#include <fmt/format.h>
#include <muParser.h>

#include <cmath>
#include <mutex>
#include <string>

namespace sdflow {

//! A parser bound to its own variables (muparser keeps pointers to them) and the lock that makes
//! an evaluation one call: setting the variables and evaluating.
struct FormulaAnisotropy::Parser {
  mu::Parser parser;
  double nx = 0, ny = 0, nz = 0;
  std::mutex mutex;

  explicit Parser(const std::string& formula)
  {
    parser.DefineVar("nx", &nx);
    parser.DefineVar("ny", &ny);
    parser.DefineVar("nz", &nz);
    parser.SetExpr(formula);
  }

  //! f(n) for a unit n; NaN where the formula cannot be evaluated.
  double operator()(const Eigen::Vector3d& n)
  {
    const std::lock_guard lock(mutex);
    nx = n.x();
    ny = n.y();
    nz = n.z();
    try {
      return parser.Eval();
    } catch (const mu::Parser::exception_type&) {
      return std::nan("");
    }
  }
};

FormulaAnisotropy::FormulaAnisotropy(const std::string& formula, bool require_convex) : formula_(formula)
{
  const auto bad = [&](const std::string& what) {
    return InvalidParameter(fmt::format("energy.formula \"{}\": {}", formula, what));
  };
  if (formula.find_first_not_of(" \t") == std::string::npos)
    throw InvalidParameter("energy.kind = \"formula\" needs energy.formula, γ as a function of the unit normal's "
                           "nx, ny, nz, for example \"1 + 0.1 * (nx^4 + ny^4 + nz^4)\"");
  try {
    parser_ = std::make_unique<Parser>(formula);
    parser_->nz = 1;
    int results = 0;
    parser_->parser.Eval(results); // muparser parses on the first evaluation: syntax errors surface here
    if (results != 1)
      throw bad(fmt::format("gives {} values; it must give one, γ(nx, ny, nz)", results));
  } catch (const mu::Parser::exception_type& e) {
    throw bad(fmt::format("does not parse: {} (at position {})", e.GetMsg(), e.GetPos()));
  }
  const std::vector<Eigen::Vector3d> directions = fibonacci_directions(2000);
  for (const Eigen::Vector3d& n : directions)
    value(n); // throws where γ is not finite and > 0
  for (const Eigen::Vector3d& n : directions) {
    if (!require_convex)
      break;
    const double gamma = value(n);
    if (const double least = least_tangent_stiffness(n); !(least >= -1e-5 * gamma))
      throw bad(fmt::format("γ is not convex: at n = ({:.4f}, {:.4f}, {:.4f}) its Hessian has the tangent eigenvalue "
                            "{:.3g}, where γ = {:.4g}. The flow of a non-convex γ is ill-posed (the weighted "
                            "curvature's diffusion runs backward); make the anisotropy weaker, or regularise it with energy.willmore",
                            n.x(), n.y(), n.z(), least, gamma));
  }
}

FormulaAnisotropy::~FormulaAnisotropy() = default;

double FormulaAnisotropy::value(const Eigen::Vector3d& p) const
{
  const double length = p.norm();
  const Eigen::Vector3d n = p / length;
  const double f = (*parser_)(n);
  // Checked at every evaluation: a flow's normals reach directions between those of the
  // construction's lattice, where a formula may still be undefined.
  if (!std::isfinite(f) || !(f > 0))
    throw InvalidParameter(fmt::format("energy.formula \"{}\": γ must be finite and > 0 for every unit normal; at "
                                       "n = ({:.4f}, {:.4f}, {:.4f}) it is {}",
                                       formula_, n.x(), n.y(), n.z(),
                                       std::isnan(f) ? std::string("undefined") : fmt::format("{}", f)));
  return length * f;
}

Eigen::Vector3d FormulaAnisotropy::gradient(const Eigen::Vector3d& p) const
{
  const double h = 1e-5 * p.norm();
  Eigen::Vector3d xi;
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector3d forward = p, backward = p;
    forward[k] += h;
    backward[k] -= h;
    xi[k] = (value(forward) - value(backward)) / (2 * h);
  }
  return xi;
}

Eigen::Matrix3d FormulaAnisotropy::hessian(const Eigen::Vector3d& p) const
{
  const double h = 2e-4 * p.norm();
  Eigen::Matrix3d hessian;
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector3d forward = p, backward = p;
    forward[k] += h;
    backward[k] -= h;
    hessian.col(k) = (gradient(forward) - gradient(backward)) / (2 * h);
  }
  return 0.5 * (hessian + hessian.transpose());
}

} // namespace sdflow
