#include "sdflow/shapes/implicit.h"

#include "sdflow/errors.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>

namespace sdflow {
namespace {

//! Central-difference step relative to the box diagonal: the truncation error (h² f''') and the
//! rounding error (ε f / h) are then both far below the projection tolerance.
constexpr double kDifferenceStep = 1e-7;

Eigen::Vector3d central_difference(const ScalarField& f, const Eigen::Vector3d& p, double h)
{
  Eigen::Vector3d g;
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector3d a = p, b = p;
    a[k] += h;
    b[k] -= h;
    g[k] = (f(a) - f(b)) / (2 * h);
  }
  return g;
}

std::string describe(const Eigen::Vector3d& p) { return fmt::format("({:.9g}, {:.9g}, {:.9g})", p.x(), p.y(), p.z()); }

//! Find f = 0 on the line p + t d (|t| ≤ reach) by bracketing a sign change and bisecting.
//! Returns false when f keeps its sign on the whole segment.
bool bisect_along_line(const ImplicitSurface& s, const Eigen::Vector3d& p, const Eigen::Vector3d& d, double reach,
                       double tolerance, Eigen::Vector3d& root)
{
  const double f0 = s.value(p);
  if (f0 == 0) {
    root = p;
    return true;
  }
  // March outwards in doubling steps on both sides until the sign changes.
  for (double t = tolerance; t <= reach; t *= 2) {
    for (const double signed_t : {t, -t}) {
      const Eigen::Vector3d q = p + signed_t * d;
      const double fq = s.value(q);
      if (!std::isfinite(fq) || (fq > 0) == (f0 > 0))
        continue;
      double a = 0, b = signed_t; // f(p + a d) has the sign of f0, f(p + b d) the other
      while (std::abs(b - a) > tolerance) {
        const double m = 0.5 * (a + b);
        const double fm = s.value(p + m * d);
        if ((fm > 0) == (f0 > 0))
          a = m;
        else
          b = m;
      }
      root = p + 0.5 * (a + b) * d;
      return true;
    }
  }
  return false;
}

} // namespace

Eigen::Vector3d level_set_gradient(const ImplicitSurface& surface, const Eigen::Vector3d& p)
{
  if (surface.gradient)
    return surface.gradient(p);
  return central_difference(surface.value, p, kDifferenceStep * surface.scale());
}

Eigen::Vector3d clip_gradient(const ImplicitSurface& surface, const Eigen::Vector3d& p)
{
  if (!surface.clipped())
    throw InvalidParameter(fmt::format("clip_gradient: surface '{}' has no clipping function", surface.name));
  if (surface.clip_gradient)
    return surface.clip_gradient(p);
  return central_difference(surface.clip, p, kDifferenceStep * surface.scale());
}

double level_set_distance(const ImplicitSurface& surface, const Eigen::Vector3d& p)
{
  const double f = surface.value(p);
  if (f == 0)
    return 0;
  const double g = level_set_gradient(surface, p).norm();
  return g > 0 ? std::abs(f) / g : std::numeric_limits<double>::infinity();
}

Eigen::Vector3d project_to_level_set(const ImplicitSurface& surface, const Eigen::Vector3d& p,
                                     const ProjectionOptions& options)
{
  const double scale = surface.scale();
  const double tolerance = options.tolerance * scale;
  Eigen::Vector3d x = p;
  Eigen::Vector3d best = p;
  double best_distance = std::numeric_limits<double>::infinity();
  for (int step = 0; step <= options.max_newton_steps; ++step) {
    const double f = surface.value(x);
    const Eigen::Vector3d g = level_set_gradient(surface, x);
    const double g2 = g.squaredNorm();
    if (!std::isfinite(f) || !(g2 > 0) || !std::isfinite(g2))
      break;
    const double distance = std::abs(f) / std::sqrt(g2);
    if (distance <= tolerance)
      return x;
    if (distance < best_distance) {
      best_distance = distance;
      best = x;
    }
    const Eigen::Vector3d next = x - (f / g2) * g;
    if ((next - p).norm() > scale) // Newton is heading away from any nearby sheet
      break;
    x = next;
  }
  // Newton stalled (a crease where two pieces alternate, or a flat gradient): bisect along the
  // gradient line through the best iterate, which brackets the surface if it is near.
  Eigen::Vector3d direction = level_set_gradient(surface, best);
  if (!(direction.norm() > 0) || !direction.allFinite())
    direction = level_set_gradient(surface, p);
  if (direction.norm() > 0 && direction.allFinite()) {
    Eigen::Vector3d root;
    if (bisect_along_line(surface, best, direction.normalized(), scale, tolerance, root))
      return root;
  }
  throw SolverFailure(fmt::format("projection onto the level set of '{}' failed from {}: f = {:.3g}, no zero "
                                  "found within {:.3g} along the gradient",
                                  surface.name, describe(p), surface.value(p), scale));
}

Eigen::Vector3d project_to_boundary_curve(const ImplicitSurface& surface, const Eigen::Vector3d& p,
                                          const ProjectionOptions& options)
{
  if (!surface.clipped())
    throw InvalidParameter(fmt::format("project_to_boundary_curve: surface '{}' has no clipping function", surface.name));
  const double tolerance = options.tolerance * surface.scale();
  Eigen::Vector3d x = p;
  for (int step = 0; step <= options.max_newton_steps; ++step) {
    const double f = surface.value(x), g = surface.clip(x);
    const Eigen::Vector3d a = level_set_gradient(surface, x), b = clip_gradient(surface, x);
    const double na = a.norm(), nb = b.norm();
    if (!(na > 0) || !(nb > 0) || !std::isfinite(f) || !std::isfinite(g))
      break;
    if (std::abs(f) / na <= tolerance && std::abs(g) / nb <= tolerance)
      return x;
    // Minimum-norm step onto the intersection of the two linearised constraints.
    Eigen::Matrix2d normal;
    normal << a.dot(a), a.dot(b), a.dot(b), b.dot(b);
    const double det = normal.determinant();
    if (!(std::abs(det) > 1e-12 * normal(0, 0) * normal(1, 1)))
      break; // the surface meets the clipping surface tangentially here
    const Eigen::Vector2d lambda = normal.inverse() * Eigen::Vector2d(f, g);
    x -= lambda[0] * a + lambda[1] * b;
  }
  throw SolverFailure(fmt::format("projection onto the boundary curve of '{}' failed from {}: the level set and "
                                  "the clipping surface do not meet transversally nearby",
                                  surface.name, describe(p)));
}

} // namespace sdflow
