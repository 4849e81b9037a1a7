#pragma once
//! \file single_precision_factor.h
//! \brief A single-precision copy of a CHOLMOD supernodal Cholesky factor L (P A Pᵀ = L Lᵀ), applied
//! as A⁻¹ ≈ Pᵀ L⁻ᵀ L⁻¹ P in float: a preconditioner for conjugate gradients that reads half the
//! bytes of the double factor. The triangular solves are memory-bound (the factor is read once
//! forward and once backward), so halving the bytes nearly halves their time; CG itself stays in
//! double, so its converged answer does not depend on the preconditioner's precision.
//! The solve follows CHOLMOD's own supernodal solves (cholmod_super_lsolve / ltsolve; Chen, Davis,
//! Hager, Rajamanickam 2008): per supernode a dense triangular solve on the diagonal block and a
//! matrix-vector product with the rows below it, gathered and scattered through its row indices.

#include <Eigen/Core>

#include <cstddef>
#include <vector>

// CHOLMOD's factor, declared rather than included so that this header needs no SuiteSparse headers.
struct cholmod_factor_struct;
typedef struct cholmod_factor_struct cholmod_factor;

namespace sdflow {

//! A float copy of a numeric supernodal LLᵀ factor of CHOLMOD's int version (the one Eigen's
//! CholmodSupernodalLLT holds); independent of the factor once constructed.
class SinglePrecisionFactor {
public:
  //! Copies `factor`'s values to float and its structure (super, pi, px, s, Perm). Throws
  //! InvalidParameter unless it is a real double supernodal LLᵀ factor with int indices, and
  //! SolverFailure if its factorisation failed (not positive definite).
  explicit SinglePrecisionFactor(const cholmod_factor& factor);

  //! ≈ A⁻¹ b = Pᵀ L⁻ᵀ L⁻¹ P b with (P b)[k] = b[Perm[k]], computed in float (relative error about
  //! cond(A) · 6e-8). Thread-safe: the workspace is the call's own. Throws InvalidParameter if
  //! b.size() ≠ size().
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;

  //! The order n of the factored matrix.
  Eigen::Index size() const { return static_cast<Eigen::Index>(permutation_.size()); }

  //! Bytes held: the float values and the copied structure arrays.
  std::size_t bytes() const;

private:
  std::vector<int> first_column_; //!< super: supernode s has columns first_column_[s] .. [s+1]-1
  std::vector<int> row_start_;    //!< pi: its row indices are rows_[row_start_[s] .. [s+1]-1]
  std::vector<int> value_start_;  //!< px: its column-major nrows × ncols block starts at values_[value_start_[s]]
  std::vector<int> rows_;         //!< s: row indices, the supernode's own columns first
  std::vector<int> permutation_;  //!< Perm: L Lᵀ = A(Perm, Perm)
  std::vector<float> values_;     //!< x, rounded to float
  Eigen::Index max_rows_below_ = 0; //!< the largest off-diagonal row count of a supernode (workspace)
};

} // namespace sdflow
