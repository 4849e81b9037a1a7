#include "sdflow/flow/single_precision_factor.h"

#include "sdflow/errors.h"

#include <cholmod.h>
#include <fmt/format.h>

#include <algorithm>

namespace sdflow {
namespace {

using FloatBlock = Eigen::Map<const Eigen::MatrixXf>;

//! The `count` ints at `data` (a CHOLMOD array), copied.
std::vector<int> copy_ints(const void* data, std::size_t count)
{
  const int* first = static_cast<const int*>(data);
  return {first, first + count};
}

//! Refuses factors this class cannot read, saying which property is wrong.
void check_factor(const cholmod_factor& factor)
{
  if (factor.itype != CHOLMOD_INT)
    throw InvalidParameter("single-precision factor: CHOLMOD factor has long indices (cholmod_l_*); "
                           "only the int version is supported");
  if (factor.xtype == CHOLMOD_PATTERN)
    throw InvalidParameter("single-precision factor: CHOLMOD factor is symbolic only (not factorised yet)");
  if (factor.xtype != CHOLMOD_REAL || factor.dtype != CHOLMOD_DOUBLE)
    throw InvalidParameter(fmt::format("single-precision factor: CHOLMOD factor must be real double, got "
                                       "xtype {} dtype {}", factor.xtype, factor.dtype));
  if (!factor.is_ll)
    throw InvalidParameter("single-precision factor: CHOLMOD factor is LDLᵀ; an LLᵀ factor is required");
  if (!factor.is_super)
    throw InvalidParameter("single-precision factor: CHOLMOD factor is simplicial; a supernodal factor is required");
  if (factor.minor < factor.n)
    throw SolverFailure(fmt::format("single-precision factor: CHOLMOD factorisation failed at column {} of {} "
                                    "(not positive definite)", factor.minor, factor.n));
}

} // namespace

SinglePrecisionFactor::SinglePrecisionFactor(const cholmod_factor& factor)
{
  check_factor(factor);
  const std::size_t supernodes = factor.nsuper;
  first_column_ = copy_ints(factor.super, supernodes + 1);
  row_start_ = copy_ints(factor.pi, supernodes + 1);
  value_start_ = copy_ints(factor.px, supernodes + 1);
  rows_ = copy_ints(factor.s, static_cast<std::size_t>(row_start_.back()));
  permutation_ = copy_ints(factor.Perm, factor.n);
  const double* x = static_cast<const double*>(factor.x);
  values_.assign(x, x + value_start_.back());
  for (std::size_t s = 0; s < supernodes; ++s) {
    const int rows_below = (row_start_[s + 1] - row_start_[s]) - (first_column_[s + 1] - first_column_[s]);
    max_rows_below_ = std::max<Eigen::Index>(max_rows_below_, rows_below);
  }
}

Eigen::VectorXd SinglePrecisionFactor::solve(const Eigen::VectorXd& b) const
{
  const Eigen::Index n = size();
  if (b.size() != n)
    throw InvalidParameter(fmt::format("single-precision factor: right-hand side has {} entries, the factor "
                                       "is {}x{}", b.size(), n, n));
  // The permutation and the rounding to float in one pass over b.
  Eigen::VectorXf y(n);
  for (Eigen::Index k = 0; k < n; ++k)
    y[k] = static_cast<float>(b[permutation_[k]]);

  Eigen::VectorXf work(max_rows_below_);
  const Eigen::Index supernodes = static_cast<Eigen::Index>(first_column_.size()) - 1;
  // Forward, L z = P b: solve with the diagonal block, then subtract the rows below from the
  // entries they touch.
  for (Eigen::Index s = 0; s < supernodes; ++s) {
    const Eigen::Index first = first_column_[s], columns = first_column_[s + 1] - first;
    const Eigen::Index rows = row_start_[s + 1] - row_start_[s], below = rows - columns;
    const FloatBlock block(values_.data() + value_start_[s], rows, columns);
    auto z = y.segment(first, columns);
    block.topRows(columns).triangularView<Eigen::Lower>().solveInPlace(z);
    if (below == 0)
      continue;
    work.head(below).noalias() = block.bottomRows(below) * z;
    const int* row = rows_.data() + row_start_[s] + columns;
    for (Eigen::Index i = 0; i < below; ++i)
      y[row[i]] -= work[i];
  }
  // Backward, Lᵀ v = z, in reverse order: gather the entries below, subtract, solve with the
  // transposed diagonal block.
  for (Eigen::Index s = supernodes - 1; s >= 0; --s) {
    const Eigen::Index first = first_column_[s], columns = first_column_[s + 1] - first;
    const Eigen::Index rows = row_start_[s + 1] - row_start_[s], below = rows - columns;
    const FloatBlock block(values_.data() + value_start_[s], rows, columns);
    auto v = y.segment(first, columns);
    if (below > 0) {
      const int* row = rows_.data() + row_start_[s] + columns;
      for (Eigen::Index i = 0; i < below; ++i)
        work[i] = y[row[i]];
      v.noalias() -= block.bottomRows(below).transpose() * work.head(below);
    }
    block.topRows(columns).transpose().triangularView<Eigen::Upper>().solveInPlace(v);
  }

  Eigen::VectorXd x(n);
  for (Eigen::Index k = 0; k < n; ++k)
    x[permutation_[k]] = y[k];
  return x;
}

std::size_t SinglePrecisionFactor::bytes() const
{
  return values_.size() * sizeof(float) +
         (first_column_.size() + row_start_.size() + value_start_.size() + rows_.size() + permutation_.size()) *
             sizeof(int);
}

} // namespace sdflow
