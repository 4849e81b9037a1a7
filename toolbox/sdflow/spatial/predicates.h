#pragma once
//! \file predicates.h
//! \brief Exact orientation predicates: a floating-point filter in front of Shewchuk's adaptive
//! `orient3d` (Shewchuk 1997), which TetGen's library exports.
//!
//! Every function returns the exact sign of its determinant for finite double inputs whose
//! products neither overflow nor underflow (coordinates between about 1e-140 and 1e140 in
//! magnitude, or exactly zero). The filter decides almost every call with a dozen flops; only
//! nearly degenerate configurations reach the adaptive exact evaluation.
//!
//! TetGen's `tetrahedralize()` reconfigures the shared predicate state for its own input (a
//! static filter sized to its bounding box, which is wrong for other inputs). Call
//! `prepare_exact_predicates()` before a batch of predicate calls that may follow a TetGen run;
//! every toolbox entry point that uses these predicates does so. Not safe to run concurrently
//! with a TetGen tetrahedralisation in another thread.

#include <cmath>

namespace sdflow::exact {

//! Put TetGen's predicates in exact, filter-free mode (cheap: a few hundred flops).
void prepare_exact_predicates();

namespace detail {
//! TetGen's adaptive orient3d; out of line so that tetgen.h stays out of this header.
double adaptive_orient3d(const double* a, const double* b, const double* c, const double* d);
//! Exact orient2d of (a, b, c) in the (u, v) plane, through orient3d of the points lifted to
//! z = 0 against (0, 0, 1).
double adaptive_orient2d(double au, double av, double bu, double bv, double cu, double cv);

// Shewchuk's error-bound coefficients for his "A" filter stage, with epsilon = 2^-53.
inline constexpr double epsilon = 1.1102230246251565e-16;
inline constexpr double orient3d_bound = (7.0 + 56.0 * epsilon) * epsilon;
inline constexpr double orient2d_bound = (3.0 + 16.0 * epsilon) * epsilon;

inline int sign(double x) { return (x > 0) - (x < 0); }
} // namespace detail

//! Sign of det[a-d, b-d, c-d]: +1 when d lies below the plane of (a, b, c), "below" meaning the
//! side from which a, b, c appear clockwise (Shewchuk's convention); 0 when the four are coplanar.
inline int orient3d(const double* a, const double* b, const double* c, const double* d)
{
  const double adx = a[0] - d[0], ady = a[1] - d[1], adz = a[2] - d[2];
  const double bdx = b[0] - d[0], bdy = b[1] - d[1], bdz = b[2] - d[2];
  const double cdx = c[0] - d[0], cdy = c[1] - d[1], cdz = c[2] - d[2];
  const double bc = bdx * cdy - cdx * bdy;
  const double ca = cdx * ady - adx * cdy;
  const double ab = adx * bdy - bdx * ady;
  const double det = adz * bc + bdz * ca + cdz * ab;
  const double permanent = (std::abs(bdx * cdy) + std::abs(cdx * bdy)) * std::abs(adz) +
                           (std::abs(cdx * ady) + std::abs(adx * cdy)) * std::abs(bdz) +
                           (std::abs(adx * bdy) + std::abs(bdx * ady)) * std::abs(cdz);
  const double bound = detail::orient3d_bound * permanent;
  if (det > bound)
    return 1;
  if (-det > bound)
    return -1;
  return detail::sign(detail::adaptive_orient3d(a, b, c, d));
}

//! Sign of ((b-a) × (c-a)) · (x-a): +1 when x lies on the side the normal of the counter-clockwise
//! triangle (a, b, c) points to. This is -orient3d(a, b, c, x).
inline int side(const double* a, const double* b, const double* c, const double* x) { return -orient3d(a, b, c, x); }

//! Sign of the 2-D orientation of (a, b, c) after dropping coordinate `axis`, keeping the two
//! others in cyclic order (y, z), (z, x) or (x, y). Equals the sign of component `axis` of
//! (b-a) × (c-a), so it is +1 for a counter-clockwise triangle seen from the positive axis.
inline int orient2d(const double* a, const double* b, const double* c, int axis)
{
  const int u = axis == 2 ? 0 : axis + 1, v = axis == 0 ? 2 : (axis == 1 ? 0 : 1);
  const double left = (a[u] - c[u]) * (b[v] - c[v]);
  const double right = (a[v] - c[v]) * (b[u] - c[u]);
  const double det = left - right;
  const double bound = detail::orient2d_bound * (std::abs(left) + std::abs(right));
  if (det > bound)
    return 1;
  if (-det > bound)
    return -1;
  return detail::sign(detail::adaptive_orient2d(a[u], a[v], b[u], b[v], c[u], c[v]));
}

//! The plane of triangle (a, b, c) prepared for many side queries. The filter evaluates the same
//! determinant, with the same rounding and error bound, as orient3d with a as the base point, but
//! the triangle's part (the cross product of its edges and the absolute values of its terms) is
//! computed once; undecided queries must go to side(a, b, c, x).
class PreparedPlane {
public:
  static constexpr int undecided = 2;

  PreparedPlane() = default;
  PreparedPlane(const double* a, const double* b, const double* c)
  {
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    for (int k = 0; k < 3; ++k) {
      const int i = (k + 1) % 3, j = (k + 2) % 3;
      base_[k] = a[k];
      normal_[k] = u[i] * w[j] - u[j] * w[i];
      terms_[k] = std::abs(u[i] * w[j]) + std::abs(u[j] * w[i]);
    }
  }

  //! side(a, b, c, x) when the filter decides it, else `undecided`.
  int filtered_side(const double* x) const
  {
    const double d0 = x[0] - base_[0], d1 = x[1] - base_[1], d2 = x[2] - base_[2];
    const double det = d0 * normal_[0] + d1 * normal_[1] + d2 * normal_[2];
    const double bound =
      detail::orient3d_bound * (std::abs(d0) * terms_[0] + std::abs(d1) * terms_[1] + std::abs(d2) * terms_[2]);
    return det > bound ? 1 : (-det > bound ? -1 : undecided);
  }

  //! The coordinate of the largest normal component as rounded: a projection that keeps the
  //! triangle large (a heuristic; exact tests in that projection stay exact whichever axis).
  int dominant_axis() const
  {
    const double n0 = std::abs(normal_[0]), n1 = std::abs(normal_[1]), n2 = std::abs(normal_[2]);
    return n0 >= n1 ? (n0 >= n2 ? 0 : 2) : (n1 >= n2 ? 1 : 2);
  }

  //! True when some normal component is certainly non-zero (orient2d's filter on each coordinate
  //! plane), so the triangle is certainly not degenerate; false means "ask projection_axis".
  bool surely_proper() const
  {
    for (int k = 0; k < 3; ++k)
      if (std::abs(normal_[k]) > detail::orient2d_bound * terms_[k])
        return true;
    return false;
  }

private:
  double base_[3] = {0, 0, 0};
  double normal_[3] = {0, 0, 0};
  double terms_[3] = {0, 0, 0};
};

//! A coordinate to drop so that triangle (a, b, c) projects to a non-degenerate 2-D triangle
//! (decided exactly, preferring the largest normal component), or -1 when the three points are
//! collinear (the triangle is degenerate).
int projection_axis(const double* a, const double* b, const double* c);

} // namespace sdflow::exact
