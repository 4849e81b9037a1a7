#include "sdflow/flow/willmore_energy.h"

#include "sdflow/errors.h"
#include "sdflow/flow/scheme.h"
#include "sdflow/geometry/cotangent_curvature.h"
#include "sdflow/geometry/laplacian.h"
#include "sdflow/geometry/normals.h"
#include "sdflow/geometry/principal_curvature.h"

#include <fmt/format.h>

#include <cmath>
#include <utility>

namespace sdflow {

WillmoreRegularisedEnergy::WillmoreRegularisedEnergy(std::shared_ptr<const SurfaceEnergy> energy, double epsilon)
    : energy_(std::move(energy)), epsilon_(epsilon)
{
  if (!std::isfinite(epsilon) || !(epsilon > 0))
    throw InvalidParameter(fmt::format("energy.willmore must be finite and > 0 for a Willmore term, got {}", epsilon));
}

double WillmoreRegularisedEnergy::value(const Mesh& mesh) const
{
  const Eigen::VectorXd areas = mixed_voronoi_areas(mesh);
  const Eigen::VectorXd h = cotangent_mean_curvature(mesh, vertex_normals(mesh), cotangent_laplacian(mesh), areas);
  return energy_->value(mesh) + 0.5 * epsilon_ * epsilon_ * (4 * h.array().square() * areas.array()).sum();
}

double WillmoreRegularisedEnergy::value_at(const Mesh& mesh, const VertexVectors& positions) const
{
  Mesh moved = mesh;
  set_vertex_positions(moved, positions);
  return value(moved);
}

Eigen::VectorXd WillmoreRegularisedEnergy::first_variation(const SurfaceGeometry& g) const
{
  for (const auto v : g.mesh.vertices())
    if (g.mesh.is_boundary(v))
      throw InvalidParameter(fmt::format("energy.willmore = {}: a Willmore term needs a closed surface; vertex {} is "
                                         "on a boundary, where the mean and Gaussian curvatures are not defined",
                                         epsilon_, v.idx()));
  Eigen::VectorXd mu = energy_->first_variation(g);
  const Eigen::VectorXd h = cotangent_mean_curvature(g.mesh, g.normals, g.laplacian, g.areas);
  const Eigen::VectorXd k = gaussian_curvature(g.mesh, g.areas);
  const Eigen::VectorXd laplacian_h = (g.laplacian * h).cwiseQuotient(g.areas);
  mu.array() -= epsilon_ * epsilon_ * (laplacian_h.array() + 2 * h.array() * (h.array().square() - k.array()));
  return mu;
}

FlowSystem WillmoreRegularisedEnergy::implicit_system(const FlowOperators& op, double tau_beta) const
{
  FlowSystem system = energy_->implicit_system(op, tau_beta);
  system.sixth_order += tau_beta * epsilon_ * epsilon_;
  return system;
}

} // namespace sdflow
