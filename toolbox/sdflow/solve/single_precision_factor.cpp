#include "sdflow/solve/single_precision_factor.h"

#include "sdflow/errors.h"

#include <cholmod.h>
#include <fmt/format.h>

#include <sys/mman.h>

#include <algorithm>
#include <cstdint>

namespace sdflow {
namespace {

// The solve reads each column of a supernode in one contiguous stream, but columns are short
// (about 170 floats at 100k vertices) and the backward pass walks them in descending order, so
// the hardware prefetcher restarts at nearly every column: the values are prefetched this many
// floats ahead in the pass's direction. Measured on bench_flow FactorApplication/100000 (4 KiB
// pages): 12 ms without, 8.0-8.5 ms with 2048 to 8192 floats (8-32 KiB) ahead.
constexpr Eigen::Index prefetch_distance = 4096;

//! Prefetches values[first, first + count) clipped to [0, size) into the cache, a cache line at a time.
void prefetch(const float* values, Eigen::Index size, Eigen::Index first, Eigen::Index count)
{
  constexpr Eigen::Index floats_per_line = 16; // 64-byte lines
  const Eigen::Index begin = std::max<Eigen::Index>(first, 0), end = std::min(first + count, size);
  for (Eigen::Index i = begin; i < end; i += floats_per_line)
    __builtin_prefetch(values + i);
}

//! Asks Linux for transparent huge pages (2 MiB) on the aligned interior of [data, data + bytes),
//! to be called before the memory is first written: streaming the factor through 4 KiB pages costs
//! a TLB miss every 1024 floats (FactorApplication/100000: 8.3 ms with 4 KiB pages, 7.5 ms with 2 MiB).
void advise_huge_pages([[maybe_unused]] const void* data, [[maybe_unused]] std::size_t bytes)
{
#ifdef MADV_HUGEPAGE
  constexpr std::uintptr_t huge_page = std::uintptr_t{2} << 20;
  const std::uintptr_t begin = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t first = (begin + huge_page - 1) / huge_page * huge_page;
  const std::uintptr_t last = (begin + bytes) / huge_page * huge_page;
  if (last > first)
    madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE); // advice only: failure is harmless
#endif
}

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
  const std::size_t value_count = static_cast<std::size_t>(value_start_.back());
  values_.reserve(value_count);
  advise_huge_pages(values_.data(), value_count * sizeof(float));
  values_.assign(x, x + value_count);
  // The diagonal entries are stored inverted: a multiplication instead of a division on the solve's
  // critical path, once per column and pass.
  for (std::size_t s = 0; s < supernodes; ++s) {
    const std::size_t rows = static_cast<std::size_t>(row_start_[s + 1] - row_start_[s]);
    const std::size_t columns = static_cast<std::size_t>(first_column_[s + 1] - first_column_[s]);
    for (std::size_t j = 0; j < columns; ++j) {
      float& diagonal = values_[static_cast<std::size_t>(value_start_[s]) + j * (rows + 1)];
      diagonal = 1.0f / diagonal;
    }
    max_rows_ = std::max(max_rows_, static_cast<Eigen::Index>(rows));
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
  // Each supernode's entries are gathered into a dense local vector, so that each column of its
  // block is read once, in one contiguous stream: forward as an axpy, backward as a dot product.
  Eigen::VectorXf local(max_rows_);
  const Eigen::Index supernodes = static_cast<Eigen::Index>(first_column_.size()) - 1;
  for (Eigen::Index s = 0; s < supernodes; ++s)
    forward_supernode(s, y, local);
  for (Eigen::Index s = supernodes - 1; s >= 0; --s)
    backward_supernode(s, y, local);
  Eigen::VectorXd x(n);
  for (Eigen::Index k = 0; k < n; ++k)
    x[permutation_[k]] = y[k];
  return x;
}

SinglePrecisionFactor::Block SinglePrecisionFactor::block(Eigen::Index s) const
{
  const Eigen::Index first = first_column_[s];
  return {first, first_column_[s + 1] - first, row_start_[s + 1] - row_start_[s], value_start_[s],
          rows_.data() + row_start_[s]};
}

void SinglePrecisionFactor::forward_supernode(Eigen::Index s, Eigen::VectorXf& y, Eigen::VectorXf& local) const
{
  const auto [first, columns, rows, start, row] = block(s);
  const Eigen::Index size = static_cast<Eigen::Index>(values_.size());
  float* const z = local.data();
  std::copy_n(y.data() + first, columns, z);
  std::fill(z + columns, z + rows, 0.0f);
  for (Eigen::Index j = 0; j < columns; ++j) {
    const Eigen::Index diagonal = start + j * rows + j;
    prefetch(values_.data(), size, diagonal + prefetch_distance, rows - j);
    const float* column = values_.data() + diagonal - j;
    const float zj = z[j] * column[j]; // the inverted diagonal
    z[j] = zj;
    for (Eigen::Index i = j + 1; i < rows; ++i)
      z[i] -= column[i] * zj;
  }
  std::copy_n(z, columns, y.data() + first);
  for (Eigen::Index i = columns; i < rows; ++i)
    y[row[i]] += z[i];
}

void SinglePrecisionFactor::backward_supernode(Eigen::Index s, Eigen::VectorXf& y, Eigen::VectorXf& local) const
{
  const auto [first, columns, rows, start, row] = block(s);
  const Eigen::Index size = static_cast<Eigen::Index>(values_.size());
  float* const z = local.data();
  std::copy_n(y.data() + first, columns, z);
  for (Eigen::Index i = columns; i < rows; ++i)
    z[i] = y[row[i]];
  for (Eigen::Index j = columns - 1; j >= 0; --j) {
    const Eigen::Index diagonal = start + j * rows + j;
    prefetch(values_.data(), size, diagonal - prefetch_distance, rows - j);
    const Eigen::Index below = rows - j - 1;
    const float dot = below > 0 ? Eigen::Map<const Eigen::VectorXf>(values_.data() + diagonal + 1, below)
                                      .dot(Eigen::Map<const Eigen::VectorXf>(z + j + 1, below))
                                : 0.0f;
    z[j] = (z[j] - dot) * values_[static_cast<std::size_t>(diagonal)];
  }
  std::copy_n(z, columns, y.data() + first);
}

std::size_t SinglePrecisionFactor::bytes() const
{
  return values_.size() * sizeof(float) +
         (first_column_.size() + row_start_.size() + value_start_.size() + rows_.size() + permutation_.size()) *
             sizeof(int);
}

} // namespace sdflow
