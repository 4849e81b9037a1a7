#pragma once
//! \file formula_anisotropy.h
//! \brief γ given by a user formula f(nx, ny, nz) on unit normals (muparser syntax), extended
//! 1-homogeneously, γ(p) = |p| f(p/|p|), with derivatives by central differences. The formula is
//! checked at construction: it parses, and on 2000 directions γ is finite, positive and convex.

#include "sdflow/geometry/anisotropy.h"

#include <memory>
#include <string>

namespace sdflow {

class FormulaAnisotropy final : public Anisotropy {
public:
  //! Throws InvalidParameter naming `energy.formula` when `formula` is empty, does not parse or
  //! gives more than one value, or when, on the 2000 directions of a Fibonacci lattice, f is not
  //! finite and > 0 or, with `require_convex`, D²γ has a negative tangent eigenvalue (below −10⁻⁵ γ:
  //! a non-convex γ, whose flow is ill-posed without a Willmore term), naming the direction.
  explicit FormulaAnisotropy(const std::string& formula, bool require_convex = true);
  ~FormulaAnisotropy() override;

  //! |p| f(p/|p|); throws InvalidParameter naming the formula and the direction where f is not
  //! finite and > 0 (between the lattice's directions, a flow's normals can still find such a spot).
  double value(const Eigen::Vector3d& p) const override;
  //! ∇γ by central differences of step 10⁻⁵ |p| (error about 10⁻¹⁰ relative for a smooth f).
  Eigen::Vector3d gradient(const Eigen::Vector3d& p) const override;
  //! D²γ by central differences of the gradient, step 2·10⁻⁴ |p| (about 10⁻⁷ relative), symmetrised.
  Eigen::Matrix3d hessian(const Eigen::Vector3d& p) const override;

  const std::string& formula() const { return formula_; }

private:
  struct Parser;
  std::string formula_;
  std::unique_ptr<Parser> parser_; // muparser evaluates through bound variables: one call at a time
};

} // namespace sdflow
