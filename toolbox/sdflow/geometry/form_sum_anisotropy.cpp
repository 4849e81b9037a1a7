#include "sdflow/geometry/form_sum_anisotropy.h"

#include "sdflow/errors.h"

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <cmath>
#include <numbers>

namespace sdflow {

Eigen::Matrix3d rotation_from_degrees(const Eigen::Vector3d& rotation_deg)
{
  const Eigen::Vector3d r = rotation_deg * (std::numbers::pi / 180);
  return (Eigen::AngleAxisd(r.z(), Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(r.y(), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(r.x(), Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

FormSumAnisotropy::FormSumAnisotropy(std::span<const AnisotropyTerm> terms)
{
  if (terms.empty())
    throw InvalidParameter("anisotropy: γ needs at least one term");
  for (std::size_t l = 0; l < terms.size(); ++l) {
    const AnisotropyTerm& t = terms[l];
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(t.g[k]) || !(t.g[k] > 0))
        throw InvalidParameter(fmt::format("anisotropy: term {} has g{} = {}; every g must be finite and > 0",
                                           l + 1, k + 1, t.g[k]));
      if (!std::isfinite(t.rotation_deg[k]))
        throw InvalidParameter(fmt::format("anisotropy: term {} has a rotation angle {} that is not finite", l + 1,
                                           t.rotation_deg[k]));
    }
    const Eigen::Matrix3d rotation = rotation_from_degrees(t.rotation_deg);
    matrices_.push_back(rotation * t.g.asDiagonal() * rotation.transpose());
  }
}

double FormSumAnisotropy::value(const Eigen::Vector3d& p) const
{
  double gamma = 0;
  for (const Eigen::Matrix3d& G : matrices_)
    gamma += std::sqrt(p.dot(G * p));
  return gamma;
}

Eigen::Vector3d FormSumAnisotropy::gradient(const Eigen::Vector3d& p) const
{
  Eigen::Vector3d xi = Eigen::Vector3d::Zero();
  for (const Eigen::Matrix3d& G : matrices_) {
    const Eigen::Vector3d Gp = G * p;
    xi += Gp / std::sqrt(p.dot(Gp));
  }
  return xi;
}

Eigen::Matrix3d FormSumAnisotropy::hessian(const Eigen::Vector3d& p) const
{
  Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();
  for (const Eigen::Matrix3d& G : matrices_) {
    const Eigen::Vector3d Gp = G * p;
    const double q = p.dot(Gp);
    hessian += (G - Gp * Gp.transpose() / q) / std::sqrt(q);
  }
  return hessian;
}

} // namespace sdflow
