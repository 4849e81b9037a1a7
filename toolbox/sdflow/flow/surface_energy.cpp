#include "sdflow/flow/surface_energy.h"

namespace sdflow {

double SurfaceEnergy::value_at(const Mesh& mesh, const VertexVectors& positions) const
{
  double energy = 0;
  for (const auto f : mesh.faces()) {
    const auto h = mesh.halfedge_handle(f);
    const Eigen::Vector3d a = positions.row(mesh.from_vertex_handle(h).idx()),
                          b = positions.row(mesh.to_vertex_handle(h).idx()),
                          c = positions.row(mesh.to_vertex_handle(mesh.next_halfedge_handle(h)).idx());
    energy += face_energy(0.5 * (b - a).cross(c - a)).value;
  }
  return energy;
}

} // namespace sdflow
