#include "sdflow/solve/supernodal_cholesky.h"

#include "sdflow/errors.h"
#include "sdflow/solve/suitesparse_output.h"

#include <Eigen/CholmodSupport>
#include <fmt/format.h>

#include <algorithm>
#include <utility>

namespace sdflow {

struct SupernodalCholesky::Impl {
  mutable cholmod_common common{};
  cholmod_factor* factor = nullptr;
  double nonzeros = 0, flops = 0;
  bool partitioned = false;

  Impl()
  {
    route_suitesparse_output();
    cholmod_start(&common);
    common.supernodal = CHOLMOD_SUPERNODAL;
    common.final_asis = 1;
  }
  ~Impl()
  {
    release();
    cholmod_finish(&common);
  }
  void release()
  {
    if (factor)
      cholmod_free_factor(&factor, &common);
    factor = nullptr;
  }
};

SupernodalCholesky::SupernodalCholesky() : impl_(std::make_unique<Impl>()) {}
SupernodalCholesky::~SupernodalCholesky() = default;
SupernodalCholesky::SupernodalCholesky(SupernodalCholesky&&) noexcept = default;
SupernodalCholesky& SupernodalCholesky::operator=(SupernodalCholesky&&) noexcept = default;

void SupernodalCholesky::analyse(const SparseMatrix& a, std::span<const int> ordering)
{
  const auto n = static_cast<std::size_t>(a.rows());
  std::vector<int> given(ordering.begin(), ordering.end());
  if (!given.empty()) {
    std::vector<char> seen(n, 0);
    const bool permutation = given.size() == n && std::all_of(given.begin(), given.end(), [&](int v) {
      return v >= 0 && static_cast<std::size_t>(v) < n && !std::exchange(seen[static_cast<std::size_t>(v)], 1);
    });
    if (!permutation)
      throw InvalidParameter(fmt::format("Cholesky analysis: the given ordering ({} entries) is not a permutation "
                                         "of the {} unknowns", given.size(), n));
  }
  Impl& m = *impl_;
  m.release();
  cholmod_sparse view = Eigen::viewAsCholmod(a.selfadjointView<Eigen::Lower>());
  if (given.empty()) {
    m.common.nmethods = 0; // CHOLMOD's default strategy
    m.factor = cholmod_analyze(&view, &m.common);
  } else {
    m.common.nmethods = 1;
    m.common.method[0].ordering = CHOLMOD_GIVEN;
    m.factor = cholmod_analyze_p(&view, given.data(), nullptr, 0, &m.common);
  }
  if (!m.factor || m.common.status < CHOLMOD_OK)
    throw SolverFailure(fmt::format("CHOLMOD symbolic analysis failed on a {}x{} system (status {})", n, n,
                                    m.common.status));
  m.nonzeros = m.common.lnz;
  m.flops = m.common.fl;
  const int method = m.common.method[m.common.selected].ordering;
  m.partitioned = given.empty() && (method == CHOLMOD_METIS || method == CHOLMOD_NESDIS);
}

bool SupernodalCholesky::factorise(const SparseMatrix& a)
{
  Impl& m = *impl_;
  if (!m.factor)
    throw SolverFailure("Cholesky factorisation before any analysis");
  cholmod_sparse view = Eigen::viewAsCholmod(a.selfadjointView<Eigen::Lower>());
  double shift[2] = {0, 0};
  cholmod_factorize_p(&view, shift, nullptr, 0, m.factor, &m.common);
  return m.common.status == CHOLMOD_OK && m.factor->minor == m.factor->n;
}

Eigen::VectorXd SupernodalCholesky::solve(const Eigen::VectorXd& b) const
{
  const Impl& m = *impl_;
  Eigen::VectorXd in = b;
  cholmod_dense view = Eigen::viewAsCholmod(in);
  cholmod_dense* x = cholmod_solve(CHOLMOD_A, m.factor, &view, &m.common);
  if (!x)
    throw SolverFailure(fmt::format("CHOLMOD triangular solves failed (status {})", m.common.status));
  Eigen::VectorXd out = Eigen::Map<const Eigen::VectorXd>(static_cast<const double*>(x->x), b.size());
  cholmod_free_dense(&x, &m.common);
  return out;
}

bool SupernodalCholesky::analysed() const { return impl_->factor != nullptr; }

std::vector<int> SupernodalCholesky::ordering() const
{
  const cholmod_factor& f = factor();
  const int* perm = static_cast<const int*>(f.Perm);
  return {perm, perm + f.n};
}

EliminationTree SupernodalCholesky::elimination_tree() const
{
  const cholmod_factor& f = factor();
  if (!f.is_super)
    throw SolverFailure("the elimination tree is read from a supernodal factor only");
  const int* super = static_cast<const int*>(f.super);
  const int* pi = static_cast<const int*>(f.pi);
  const int* rows = static_cast<const int*>(f.s);
  EliminationTree tree{ordering(), std::vector<int>(f.n, -1)};
  // Within a supernode each column's parent is the next; the last column's is the supernode's first
  // row below its dense diagonal block.
  for (std::size_t s = 0; s < f.nsuper; ++s) {
    const int first = super[s], end = super[s + 1];
    for (int j = first; j + 1 < end; ++j)
      tree.parent[static_cast<std::size_t>(j)] = j + 1;
    const int columns = end - first;
    if (pi[s + 1] - pi[s] > columns)
      tree.parent[static_cast<std::size_t>(end - 1)] = rows[pi[s] + columns];
  }
  return tree;
}

bool SupernodalCholesky::partitioned() const { return impl_->partitioned; }

double SupernodalCholesky::factor_nonzeros() const { return impl_->nonzeros; }
double SupernodalCholesky::factorisation_flops() const { return impl_->flops; }

const cholmod_factor& SupernodalCholesky::factor() const
{
  if (!impl_->factor)
    throw SolverFailure("Cholesky factor asked for before any analysis");
  return *impl_->factor;
}

} // namespace sdflow
