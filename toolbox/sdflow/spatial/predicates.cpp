#include "sdflow/spatial/predicates.h"

#include <tetgen.h>

#include <array>
#include <cmath>

namespace sdflow::exact {

void prepare_exact_predicates()
{
  // verbose = 0, noexact = 0 (adaptive exact arithmetic), nofilter = 1 (no static filter: it
  // depends on the bounding box passed here, which is not ours to know). The box must be positive.
  ::exactinit(0, 0, 1, 1.0, 1.0, 1.0);
}

namespace detail {

double adaptive_orient3d(const double* a, const double* b, const double* c, const double* d)
{
  // TetGen declares its arguments non-const but only reads them.
  return ::orient3d(const_cast<double*>(a), const_cast<double*>(b), const_cast<double*>(c), const_cast<double*>(d));
}

double adaptive_orient2d(double au, double av, double bu, double bv, double cu, double cv)
{
  // det[(a,0)-(0,0,1), (b,0)-(0,0,1), (c,0)-(0,0,1)] = -orient2d(a, b, c); every difference
  // with the lifted apex is exact, so the adaptive orient3d decides the 2-D sign exactly.
  double pa[3] = {au, av, 0.0}, pb[3] = {bu, bv, 0.0}, pc[3] = {cu, cv, 0.0}, apex[3] = {0.0, 0.0, 1.0};
  return -::orient3d(pa, pb, pc, apex);
}

} // namespace detail

int projection_axis(const double* a, const double* b, const double* c)
{
  const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
  const double vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
  const std::array<double, 3> n = {std::abs(uy * vz - uz * vy), std::abs(uz * vx - ux * vz), std::abs(ux * vy - uy * vx)};
  std::array<int, 3> order = {0, 1, 2};
  if (n[order[1]] > n[order[0]])
    std::swap(order[0], order[1]);
  if (n[order[2]] > n[order[1]])
    std::swap(order[1], order[2]);
  if (n[order[1]] > n[order[0]])
    std::swap(order[0], order[1]);
  for (int axis : order)
    if (orient2d(a, b, c, axis) != 0)
      return axis;
  return -1;
}

} // namespace sdflow::exact
