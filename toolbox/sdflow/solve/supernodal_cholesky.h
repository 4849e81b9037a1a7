#pragma once
//! \file supernodal_cholesky.h
//! \brief CHOLMOD's supernodal LLᵀ factorisation (Chen, Davis, Hager, Rajamanickam 2008) of an SPD
//! matrix, with the fill-reducing ordering either CHOLMOD's own choice or one the caller gives
//! (cholmod_analyze_p), so that a re-triangulated surface can reuse its predecessor's ordering.

#include "sdflow/geometry/laplacian.h"

#include <Eigen/Core>

#include <memory>
#include <span>
#include <vector>

struct cholmod_factor_struct;

namespace sdflow {

//! An elimination order and its tree, in elimination ranks: row k of the factor is vertex
//! ordering[k], parent[k] > k is the rank of its parent (-1 for a root). Children precede parents
//! and every subtree is a contiguous range of ranks (a postorder), as CHOLMOD's analysis leaves them.
struct EliminationTree {
  std::vector<int> ordering;
  std::vector<int> parent;
};

class SupernodalCholesky {
public:
  SupernodalCholesky();
  ~SupernodalCholesky();
  SupernodalCholesky(SupernodalCholesky&&) noexcept;
  SupernodalCholesky& operator=(SupernodalCholesky&&) noexcept;

  //! Symbolic analysis of the pattern of `a` (symmetric; its lower triangle is read). Without
  //! `ordering`, CHOLMOD chooses the ordering (AMD, then METIS if AMD's fill is high); with one (a
  //! permutation of 0..n-1, row k of the factor is vertex ordering[k]) only that ordering is used,
  //! followed by CHOLMOD's weighted postorder. Throws SolverFailure if CHOLMOD fails,
  //! InvalidParameter if `ordering` is not a permutation of the right size.
  void analyse(const SparseMatrix& a, std::span<const int> ordering = {});

  //! Numeric factorisation of `a`, whose pattern must be the analysed one; false if `a` is not
  //! positive definite to working precision.
  bool factorise(const SparseMatrix& a);

  //! A⁻¹ b by the forward and backward triangular solves with the factor.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;

  bool analysed() const;
  //! The analysis's ordering, postordered: row k of the factor is vertex ordering()[k].
  std::vector<int> ordering() const;
  //! The analysis's ordering with the elimination tree of the factor's stored pattern.
  EliminationTree elimination_tree() const;
  //! Whether the analysis's ordering came from graph partitioning (METIS or CHOLMOD's nested
  //! dissection), the costly kind, rather than from AMD or the caller.
  bool partitioned() const;
  //! Non-zeros of the factor L and flops of one numeric factorisation, as the analysis predicts.
  double factor_nonzeros() const;
  double factorisation_flops() const;
  //! CHOLMOD's factor (supernodal, LLᵀ once factorised), for single-precision copies of it.
  const cholmod_factor_struct& factor() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace sdflow
