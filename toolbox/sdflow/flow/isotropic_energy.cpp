#include "sdflow/flow/isotropic_energy.h"

#include "sdflow/flow/scheme.h"
#include "sdflow/geometry/cotangent_curvature.h"
#include "sdflow/geometry/measures.h"

namespace sdflow {

double IsotropicEnergy::value(const Mesh& mesh) const { return surface_area(mesh); }

Eigen::VectorXd IsotropicEnergy::first_variation(const SurfaceGeometry& g) const
{
  // The cotangent H is built from the L and M just assembled rather than assembling them again.
  return curvature_.method == CurvatureMethod::cotangent
             ? cotangent_mean_curvature(g.mesh, g.normals, g.laplacian, g.areas)
             : mean_curvature(g.mesh, g.normals, curvature_);
}

FlowSystem IsotropicEnergy::implicit_system(const FlowOperators& op, double tau_beta) const
{
  return {op.laplacian, op.areas, op.held, tau_beta};
}

FaceEnergy IsotropicEnergy::face_energy(const Eigen::Vector3d& a) const
{
  const double length = a.norm();
  const Eigen::Vector3d n = a / length;
  return {length, n, (Eigen::Matrix3d::Identity() - n * n.transpose()) / length};
}

} // namespace sdflow
