#include "sdflow/flow/fixed_boundary.h"

#include "sdflow/errors.h"

#include <fmt/format.h>

#include <cmath>
#include <utility>

namespace sdflow {

namespace {

//! A rim vertex's interior neighbours j with L_bj, and whether the star rule applies to it.
struct RimStar {
  std::vector<std::pair<int, double>> interior;
  double weight = 0; //!< d_b = Σ L_bj over the interior neighbours
  bool eliminated() const
  {
    double magnitude = 0;
    for (const auto& [j, l] : interior)
      magnitude += std::abs(l);
    return weight > kRimEliminationFraction * magnitude && weight > 0;
  }
};

RimStar rim_star(const SparseMatrix& laplacian, const std::vector<bool>& rim, Eigen::Index b)
{
  RimStar star;
  for (SparseMatrix::InnerIterator it(laplacian, b); it; ++it) // column b = row b (L symmetric)
    if (!rim[static_cast<std::size_t>(it.row())]) {
      star.interior.emplace_back(static_cast<int>(it.row()), it.value());
      star.weight += it.value();
    }
  return star;
}

} // namespace

SparseMatrix zero_flux_laplacian(const SparseMatrix& laplacian, const std::vector<bool>& rim)
{
  const Eigen::Index n = laplacian.rows();
  if (laplacian.cols() != n || static_cast<Eigen::Index>(rim.size()) != n)
    throw InvalidParameter(fmt::format("zero_flux_laplacian: a {}×{} Laplacian and {} rim flags", laplacian.rows(),
                                       laplacian.cols(), rim.size()));
  using Triplet = Eigen::Triplet<double>;
  std::vector<Triplet> entries;
  entries.reserve(static_cast<std::size_t>(laplacian.nonZeros()));
  for (Eigen::Index j = 0; j < laplacian.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(laplacian, j); it; ++it) {
      const bool cut = rim[static_cast<std::size_t>(it.row())] || rim[static_cast<std::size_t>(j)];
      entries.emplace_back(static_cast<int>(it.row()), static_cast<int>(j), cut ? 0.0 : it.value());
    }
  for (Eigen::Index b = 0; b < n; ++b) {
    if (!rim[static_cast<std::size_t>(b)])
      continue;
    const RimStar star = rim_star(laplacian, rim, b);
    const bool eliminated = star.eliminated();
    // Every pair of interior neighbours gets its entry, zero or not, so that the pattern (hence the
    // solver's symbolic analysis) does not depend on the values.
    for (const auto& [j, ljb] : star.interior)
      for (const auto& [k, lbk] : star.interior)
        entries.emplace_back(j, k, eliminated ? ljb * lbk / star.weight : 0.0);
    if (!eliminated) // cut: the edge's weight leaves the diagonal with it, so rows still sum to zero
      for (const auto& [j, ljb] : star.interior)
        entries.emplace_back(j, j, ljb);
  }
  SparseMatrix s(n, n);
  s.setFromTriplets(entries.begin(), entries.end());
  return s;
}

void FixedBoundary::impose(const Mesh& mesh, SparseMatrix& laplacian, Eigen::VectorXd& first_variation,
                           std::vector<bool>& held) const
{
  held.clear();
  std::vector<bool> rim(mesh.n_vertices(), false);
  bool any = false;
  for (auto v : mesh.vertices())
    if (mesh.is_boundary(v))
      rim[static_cast<std::size_t>(v.idx())] = any = true;
  if (!any)
    return;
  for (Eigen::Index b = 0; b < static_cast<Eigen::Index>(rim.size()); ++b) {
    if (!rim[static_cast<std::size_t>(b)])
      continue;
    const RimStar star = rim_star(laplacian, rim, b);
    double h = 0;
    if (star.eliminated()) {
      for (const auto& [j, l] : star.interior)
        h += l * first_variation[j];
      h /= star.weight;
    } else if (!star.interior.empty()) {
      for (const auto& [j, l] : star.interior)
        h += first_variation[j];
      h /= static_cast<double>(star.interior.size());
    }
    first_variation[b] = h;
  }
  laplacian = zero_flux_laplacian(laplacian, rim);
  held = std::move(rim);
}

} // namespace sdflow
