#pragma once
//! \file single_precision_factor.h
//! \brief A single-precision copy of a CHOLMOD supernodal Cholesky factor L (P A Pᵀ = L Lᵀ), applied
//! as A⁻¹ ≈ Pᵀ L⁻ᵀ L⁻¹ P in float: a preconditioner for conjugate gradients that reads half the
//! bytes of the double factor. The triangular solves are memory-bound (the factor is read once
//! forward and once backward); CG itself stays in double, so its converged answer does not depend
//! on the preconditioner's precision, only its iteration count may (by float's rounding, relative
//! 1e-6 at 100k-400k vertices on the flow step's matrix: bench_flow FactorApplication).
//! The structure is CHOLMOD's (cholmod_super_lsolve / ltsolve; Chen, Davis, Hager, Rajamanickam
//! 2008): supernode s has columns super[s] .. super[s+1]-1 and row indices s[pi[s] .. pi[s+1]-1]
//! (its own columns first); its values are a column-major rows × columns block at x[px[s]], the
//! dense lower triangle on top. Each supernode's entries are gathered into a dense vector and its
//! block is read one column at a time, in one contiguous stream per column: an axpy forward, a dot
//! product backward, each with the triangular part and the rows below fused.

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
  //! Where supernode s lies: its columns first .. first + columns - 1, its row count, the start of
  //! its values, its row indices.
  struct Block {
    Eigen::Index first, columns, rows, start;
    const int* row;
  };
  Block block(Eigen::Index s) const;

  //! Forward substitution through supernode s (L z = y on its columns, then the rows below updated),
  //! in place in y; `local` holds at least max_rows_ floats of workspace.
  void forward_supernode(Eigen::Index s, Eigen::VectorXf& y, Eigen::VectorXf& local) const;
  //! Backward substitution through supernode s (Lᵀ z = y on its columns given the rows below), in
  //! place in y; `local` as in forward_supernode.
  void backward_supernode(Eigen::Index s, Eigen::VectorXf& y, Eigen::VectorXf& local) const;

  std::vector<int> first_column_; //!< super: supernode s has columns first_column_[s] .. [s+1]-1
  std::vector<int> row_start_;    //!< pi: its row indices are rows_[row_start_[s] .. [s+1]-1]
  std::vector<int> value_start_;  //!< px: its column-major nrows × ncols block starts at values_[value_start_[s]]
  std::vector<int> rows_;         //!< s: row indices, the supernode's own columns first
  std::vector<int> permutation_;  //!< Perm: L Lᵀ = A(Perm, Perm)
  std::vector<float> values_;     //!< x rounded to float, the diagonal entries inverted
  Eigen::Index max_rows_ = 0; //!< the largest row count of a supernode (workspace)
};

} // namespace sdflow
