#pragma once
//! \file dumbbell.h
//! \brief The dumbbell of paper §3.2.2: two spheres joined by a parabolic isthmus, C¹ profile.
//!
//! The surface is the revolution about the x axis of the profile ρ(x), |x| ≤ c + R:
//!   ρ(x) = ρ₀ + k x²                 for |x| ≤ t   (the isthmus, narrowest width 2ρ₀ at x = 0)
//!   ρ(x) = √(R² − (|x| − c)²)        for t ≤ |x| ≤ c + R (arcs of the end circles, centres ±c)
//! The join abscissa t and the coefficient k are fixed by continuity of ρ and of ρ' at |x| = t
//! (the parabola is tangent to the circle). With u = c − t and ρ_t = √(R² − u²) the two conditions
//! reduce to one equation in u,
//!   2 ρ_t (ρ_t − ρ₀) = (c − u) u,      then  k = (ρ_t − ρ₀) / t²,
//! which has a root in (0, R) whenever ρ₀ < R < c; it is found by bisection. With the paper's
//! R = 6, width 1 and the default centre separation 2c = 18 (not stated in the paper): t ≈ 4.08,
//! ρ_t ≈ 3.43, k ≈ 0.176; the dumbbell spans |x| ≤ 15.

namespace sdflow {

struct DumbbellParameters {
  double radius = 6;      //!< R, radius of the end circles (paper: "semicircles of radius 6")
  double neck_width = 1;  //!< 2ρ₀, width of the isthmus at its narrowest (paper: 1)
  double separation = 18; //!< 2c, distance between the centres of the end circles (> 2R)
};

//! The meridian profile ρ(x) and the exact signed distance to the surface in the meridian plane.
class DumbbellProfile {
public:
  //! Throws InvalidParameter unless 0 < neck_width / 2 < radius < separation / 2.
  explicit DumbbellProfile(const DumbbellParameters& parameters = {});

  const DumbbellParameters& parameters() const { return parameters_; }
  double join() const { return join_; }            //!< t: the isthmus is |x| ≤ t
  double coefficient() const { return k_; }        //!< k of ρ₀ + k x²
  double half_length() const { return centre_ + parameters_.radius; } //!< c + R

  //! ρ(x); 0 outside |x| ≤ c + R.
  double radius_at(double x) const;
  //! ρ'(x) for |x| < c + R.
  double slope_at(double x) const;

  //! Signed Euclidean distance from the point (x, r), r ≥ 0 the distance to the axis, to the
  //! profile curve: negative inside. `gradient` (optional) receives ∂/∂x and ∂/∂r.
  double signed_distance(double x, double r, double* gradient_x = nullptr, double* gradient_r = nullptr) const;

  double volume() const; //!< enclosed volume, by Pappus' theorem on ρ (exact)
  double area() const;   //!< surface area (composite Simpson on the isthmus, exact on the caps)

private:
  DumbbellParameters parameters_;
  double rho0_ = 0, centre_ = 0, join_ = 0, join_radius_ = 0, k_ = 0, join_angle_ = 0;
};

} // namespace sdflow
