#include "sdflow/solve/carried_ordering.h"

#include "sdflow/errors.h"

#include <fmt/format.h>

#include <numeric>

namespace sdflow {
namespace {

//! The old tree with O(1) subtree tests: subtree(k) is the rank range [first[k], k]; `top[k]` is the
//! last rank of the chain k, k+1, ... of single-child parents that share k's subtree start.
class RankTree {
public:
  explicit RankTree(const std::vector<int>& parent) : parent_(parent), first_(parent.size()), top_(parent.size())
  {
    const int n = static_cast<int>(parent.size());
    std::iota(first_.begin(), first_.end(), 0);
    for (int k = 0; k < n; ++k) {
      const int p = parent[static_cast<std::size_t>(k)];
      if (p != -1 && (p <= k || p >= n))
        throw InvalidParameter(fmt::format("carried ordering: rank {} has parent {} (not a postordered tree)", k, p));
      if (p != -1)
        first_[static_cast<std::size_t>(p)] = std::min(first_[static_cast<std::size_t>(p)], first_[static_cast<std::size_t>(k)]);
    }
    for (int k = n - 1; k >= 0; --k) {
      const int p = parent[static_cast<std::size_t>(k)];
      top_[static_cast<std::size_t>(k)] =
          p == k + 1 && first_[static_cast<std::size_t>(p)] == first_[static_cast<std::size_t>(k)] ? top_[static_cast<std::size_t>(p)] : k;
    }
  }
  int size() const { return static_cast<int>(parent_.size()); }
  //! Whether a is b or below it.
  bool within(int a, int b) const { return first_[static_cast<std::size_t>(b)] <= a && a <= b; }
  //! The lowest common ancestor of a and b, or size() (a virtual root) if they lie in different trees.
  int common_ancestor(int a, int b) const
  {
    for (int x = a;;) {
      if (within(b, x))
        return x;
      const int end = top_[static_cast<std::size_t>(x)];
      if (first_[static_cast<std::size_t>(x)] <= b && b <= end)
        return b; // b is on x's chain, above x
      x = parent_[static_cast<std::size_t>(end)];
      if (x == -1)
        return size();
    }
  }

private:
  const std::vector<int>& parent_;
  std::vector<int> first_, top_;
};

} // namespace

std::vector<int> carried_ordering(const EliminationTree& old, std::span<const int> nearest_old,
                                  const SparseMatrix& laplacian)
{
  const std::size_t old_count = old.ordering.size();
  if (old.parent.size() != old_count)
    throw InvalidParameter(fmt::format("carried ordering: {} ranks but {} parents", old_count, old.parent.size()));
  std::vector<int> rank(old_count, -1);
  for (std::size_t k = 0; k < old_count; ++k) {
    const int v = old.ordering[k];
    if (v < 0 || static_cast<std::size_t>(v) >= old_count || rank[static_cast<std::size_t>(v)] >= 0)
      throw InvalidParameter(fmt::format("carried ordering: the old ordering is not a permutation (entry {} is {})", k, v));
    rank[static_cast<std::size_t>(v)] = static_cast<int>(k);
  }
  const RankTree tree(old.parent);
  const std::size_t count = nearest_old.size();
  if (laplacian.rows() != static_cast<Eigen::Index>(count) || laplacian.cols() != laplacian.rows())
    throw InvalidParameter(fmt::format("carried ordering: {} new vertices but a {}x{} Laplacian", count,
                                       laplacian.rows(), laplacian.cols()));
  std::vector<int> key(count);
  for (std::size_t u = 0; u < count; ++u) {
    if (nearest_old[u] < 0 || static_cast<std::size_t>(nearest_old[u]) >= old_count)
      throw InvalidParameter(fmt::format("carried ordering: new vertex {} has nearest old vertex {} of {}", u,
                                         nearest_old[u], old_count));
    key[u] = rank[static_cast<std::size_t>(nearest_old[u])];
  }
  // Lifting u to a common ancestor keeps every relation u already had comparable (two ancestors of
  // one rank are comparable), so one pass over the couplings (two rings in L) mends all of them.
  const auto comparable = [&](int a, int b) {
    return a == tree.size() || b == tree.size() || tree.within(a, b) || tree.within(b, a);
  };
  for (Eigen::Index u = 0; u < laplacian.outerSize(); ++u)
    for (SparseMatrix::InnerIterator near(laplacian, u); near; ++near)
      for (SparseMatrix::InnerIterator far(laplacian, near.row()); far; ++far) {
        int& ku = key[static_cast<std::size_t>(u)];
        const int kw = key[static_cast<std::size_t>(far.row())];
        if (!comparable(ku, kw))
          ku = tree.common_ancestor(ku, kw);
      }
  // A counting sort by key: stable, so ties keep the new vertices' order.
  std::vector<std::size_t> start(old_count + 2, 0);
  for (const int k : key)
    ++start[static_cast<std::size_t>(k) + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<int> order(count);
  for (std::size_t u = 0; u < count; ++u)
    order[start[static_cast<std::size_t>(key[u])]++] = static_cast<int>(u);
  return order;
}

} // namespace sdflow
