#include "sdflow/flow/substrate_boundary.h"

#include "sdflow/errors.h"
#include "sdflow/flow/scheme.h"
#include "sdflow/flow/substrate_topology_hook.h"
#include "sdflow/geometry/material_volume.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/topology.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace sdflow {
namespace {

//! A rim vertex b's contact-line geometry: its outward in-plane normal n̂_b, ℓ_b, k_b, and the
//! gradients of which cos θ_d is made with the film's pressure (contact_angle_cosine).
struct ContactPoint {
  int vertex = 0;
  Eigen::Vector3d outward = Eigen::Vector3d::Zero();
  double half_chord = 0; //!< ℓ_b = |∂A_base/∂x_b|
  Eigen::Vector3d energy_gradient = Eigen::Vector3d::Zero(); //!< ∂E_h/∂x_b (E_h the area for the isotropic energy)
  Eigen::Vector3d volume_gradient = Eigen::Vector3d::Zero(); //!< ∂V/∂x_b
  double stiffness = 0;  //!< k_b = n̂ᵀ ∂²E_h/∂x_b² n̂ / ℓ_b
};

//! Each film component's pressure λ = Σ_v ∂E_h/∂x_v·N_v / Σ_v ∂V/∂x_v·N_v over its vertices off the
//! rim: the energy a normal offset of its interior (move_rim's volume correction) trades per unit
//! of volume, the discrete Lagrange multiplier of the volume. `component` gives each vertex's
//! component (rim vertices included), `offset_rate` the denominator, the volume's rate under the offset.
struct InteriorPressure {
  std::vector<int> component;
  std::vector<double> pressure, offset_rate;
};

//! λ of each of the `count` components of `mesh` (`face_component`, as face_component_ids gives
//! them) at vertex positions `x`, with the normals of `op`.
InteriorPressure interior_pressure(const Mesh& mesh, const VertexVectors& x, const FlowOperators& op,
                                   const std::vector<int>& face_component, int count)
{
  InteriorPressure p{std::vector<int>(static_cast<std::size_t>(x.rows()), -1),
                     std::vector<double>(static_cast<std::size_t>(count), 0.0),
                     std::vector<double>(static_cast<std::size_t>(count), 0.0)};
  std::vector<double> energy_rate(static_cast<std::size_t>(count), 0.0);
  for (const auto f : mesh.faces()) {
    const std::size_t k = static_cast<std::size_t>(face_component[static_cast<std::size_t>(f.idx())]);
    std::array<int, 3> v{};
    int c = 0;
    for (const auto u : mesh.fv_range(f))
      v[static_cast<std::size_t>(c++)] = u.idx();
    const Eigen::Vector3d x0 = x.row(v[0]), x1 = x.row(v[1]), x2 = x.row(v[2]);
    const FaceEnergy face = op.parts.energy->face_energy(0.5 * (x1 - x0).cross(x2 - x0));
    for (c = 0; c < 3; ++c) {
      const int corner = v[static_cast<std::size_t>(c)];
      p.component[static_cast<std::size_t>(corner)] = static_cast<int>(k);
      if (mesh.is_boundary(Mesh::VertexHandle(corner)))
        continue;
      const Eigen::Vector3d a = x.row(v[static_cast<std::size_t>((c + 1) % 3)]),
                            b = x.row(v[static_cast<std::size_t>((c + 2) % 3)]);
      const Eigen::Vector3d normal = op.normals.row(corner).transpose();
      energy_rate[k] += (0.5 * (a - b).cross(face.gradient)).dot(normal);
      p.offset_rate[k] += a.cross(b).dot(normal) / 6.0; // an interior star is closed: any origin
    }
  }
  for (std::size_t k = 0; k < p.pressure.size(); ++k)
    p.pressure[k] = std::abs(p.offset_rate[k]) > 0 ? energy_rate[k] / p.offset_rate[k] : 0.0;
  return p;
}

//! The same, with the components of `mesh` found here.
InteriorPressure interior_pressure(const Mesh& mesh, const VertexVectors& x, const FlowOperators& op)
{
  int count = 0;
  const std::vector<int> face_component = face_component_ids(mesh, &count);
  return interior_pressure(mesh, x, op, face_component, count);
}

//! The contact points of every boundary loop, loop by loop, on the substrate z = `z0`. A boundary
//! loop runs against its faces, so with the film's normals outward it turns clockwise seen from
//! above and e_z × (x_{b+1} − x_{b−1}) points out of the film: it is 2 ∂A_base/∂x_b, the base
//! polygon's area gradient.
std::vector<ContactPoint> contact_points(const Mesh& mesh, const VertexVectors& x, const FlowOperators& op, double z0)
{
  std::vector<ContactPoint> points;
  const Eigen::Vector3d origin(0, 0, z0); // on the plane, where the loops' caps hold no volume
  for (const auto& loop : boundary_loops(mesh)) {
    const std::size_t n = loop.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Mesh::VertexHandle b = mesh.from_vertex_handle(loop[i]);
      const int prev = mesh.from_vertex_handle(loop[(i + n - 1) % n]).idx(), next = mesh.to_vertex_handle(loop[i]).idx();
      const Eigen::Vector3d chord(x(next, 0) - x(prev, 0), x(next, 1) - x(prev, 1), 0.0);
      ContactPoint p;
      p.vertex = b.idx();
      p.half_chord = 0.5 * chord.norm();
      if (!(p.half_chord > 0))
        throw InvalidMesh(fmt::format("substrate: the contact line folds back on itself at vertex {}", p.vertex));
      p.outward = Eigen::Vector3d(-chord.y(), chord.x(), 0.0) / chord.norm();
      double curvature = 0;
      const Eigen::Vector3d xb = x.row(p.vertex);
      for (const auto h : mesh.voh_range(b)) {
        if (mesh.is_boundary(h))
          continue;
        const Eigen::Vector3d xp = x.row(mesh.to_vertex_handle(h).idx());
        const Eigen::Vector3d xq = x.row(mesh.to_vertex_handle(mesh.next_halfedge_handle(h)).idx());
        const Eigen::Vector3d area_vector = 0.5 * (xp - xb).cross(xq - xb);
        if (!(area_vector.norm() > 0))
          throw InvalidMesh(fmt::format("substrate: a degenerate triangle at contact-line vertex {}", p.vertex));
        // a moves by ½ δ n̂ × (x_p − x_q) as b moves by δ n̂: E_f = γ(a) changes at ξ(a)·u, and is
        // convex along n̂ with second derivative uᵀ D²γ(a) u (for the area, |e|² (n̂·N_f)² / (4 |f|)).
        const FaceEnergy face = op.parts.energy->face_energy(area_vector);
        const Eigen::Vector3d u = 0.5 * p.outward.cross(xp - xq);
        p.energy_gradient += 0.5 * (xp - xq).cross(face.gradient);
        p.volume_gradient += (xp - origin).cross(xq - origin) / 6.0;
        curvature += u.dot(face.hessian * u);
      }
      p.stiffness = curvature / p.half_chord;
      points.push_back(p);
    }
  }
  return points;
}

//! cos θ_d = ((∂E_h/∂x_b − λ ∂V/∂x_b) · n̂_b) / ℓ_b at the contact point `p`, λ its component's
//! pressure in `interior`. Less the pressure's part, λ ∂V/∂x_b: it is balanced by the volume, not by
//! the contact line (on an exact cap cos θ_d is then off by O(h), which moves the rim by O(h²)
//! only). With the λ of the interior offset that gives the swept volume back, rim and offset
//! together lower W_h (docs/method.md, "Substrate", "Energy").
double contact_angle_cosine(const ContactPoint& p, const InteriorPressure& interior)
{
  Eigen::Vector3d gradient = p.energy_gradient;
  gradient -= interior.pressure[static_cast<std::size_t>(interior.component[static_cast<std::size_t>(p.vertex)])] *
              p.volume_gradient;
  return gradient.dot(p.outward) / p.half_chord;
}

//! Whether the highest vertex of component k lies inside the material of the other components: a
//! ray from it, upward (tilted off the axes, so that it meets no edge of an axis-aligned mesh), crosses
//! their faces an odd number of times (Möller–Trumbore). It never meets the caps over the contact
//! lines, which lie in the substrate's plane below it. A component of negative material volume
//! there is a pocket of vapour that the film closed over on the substrate, not a film turned inside out.
bool inside_other_components(const VertexVectors& x, const FaceIndices& faces, const std::vector<int>& component,
                             int k)
{
  Eigen::Index top = -1;
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    if (component[static_cast<std::size_t>(f)] == k)
      for (int c = 0; c < 3; ++c)
        if (top < 0 || x(faces(f, c), 2) > x(top, 2))
          top = faces(f, c);
  if (top < 0)
    return false;
  const Eigen::Vector3d origin = x.row(top), direction = Eigen::Vector3d(0.0013, 0.0021, 1).normalized();
  int crossings = 0;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    if (component[static_cast<std::size_t>(f)] == k)
      continue;
    const Eigen::Vector3d a = x.row(faces(f, 0)), b = x.row(faces(f, 1)), c = x.row(faces(f, 2));
    const Eigen::Vector3d e1 = b - a, e2 = c - a, p = direction.cross(e2);
    const double det = e1.dot(p);
    if (std::abs(det) < 1e-300)
      continue;
    const Eigen::Vector3d s = origin - a;
    const double u = s.dot(p) / det;
    const Eigen::Vector3d q = s.cross(e1);
    const double v = direction.dot(q) / det;
    const double t = e2.dot(q) / det;
    crossings += u >= 0 && v >= 0 && u + v <= 1 && t > 0;
  }
  return crossings % 2 == 1;
}

} // namespace

SubstrateBoundary::SubstrateBoundary(const SubstrateOptions& options) : options_(options)
{
  const SubstrateRanges& r = substrate_ranges;
  if (!r.contact_angle.contains(options.contact_angle))
    throw InvalidParameter(fmt::format("substrate.contact_angle must be {} degrees, got {}", r.contact_angle.text(),
                                       options.contact_angle));
  if (!r.mobility.contains(options.mobility))
    throw InvalidParameter(fmt::format("substrate.mobility must be {} (inf holds the contact angle), got {}",
                                       r.mobility.text(), options.mobility));
  if (!r.z.contains(options.z))
    throw InvalidParameter(fmt::format("substrate.z must be finite, got {}", options.z));
}

void SubstrateBoundary::check_surface(const Mesh& mesh, const UserTerms& terms) const
{
  const std::string plane = terms.setting("substrate.z", fmt::format("{}", options_.z));
  const VertexVectors x = vertex_positions(mesh);
  if (x.rows() == 0)
    return;
  const double size = (x.colwise().maxCoeff() - x.colwise().minCoeff()).norm();
  const double tolerance = 1e-9 * std::max(size, std::abs(options_.z));
  const auto loops = boundary_loops(mesh);
  for (std::size_t l = 0; l < loops.size(); ++l)
    for (const auto h : loops[l]) {
      const int v = mesh.from_vertex_handle(h).idx();
      if (std::abs(x(v, 2) - options_.z) > tolerance)
        throw InvalidParameter(fmt::format(
          "on a substrate, boundary loop {} ({} vertices) is not on the plane ({}): its vertex {} has z = {}; every "
          "boundary loop must be a contact line on the substrate's plane",
          l, loops[l].size(), plane, v, x(v, 2)));
    }
  for (Eigen::Index v = 0; v < x.rows(); ++v)
    if (x(v, 2) < options_.z - tolerance)
      throw InvalidParameter(fmt::format("on a substrate, vertex {} has z = {}, below the substrate ({}); the film "
                                         "must lie above its plane",
                                         v, x(v, 2), plane));
  int count = 0;
  const std::vector<int> component = face_component_ids(mesh, &count);
  const std::vector<BoundaryLoop> rims = boundary_loop_vertices(mesh, component);
  const FaceIndices faces = face_indices(mesh);
  const std::vector<double> volumes = material_volumes(x, faces, component, count, rims);
  for (std::size_t l = 0; l < rims.size(); ++l) {
    const double volume = volumes[static_cast<std::size_t>(rims[l].component)];
    if (!(volume > 0) && !(volume < 0 && inside_other_components(x, faces, component, rims[l].component)))
      throw InvalidParameter(fmt::format("on a substrate, the component of boundary loop {} bounds the material "
                                         "volume {} with the substrate's plane ({}), not a positive one: its "
                                         "normals must point out of the film",
                                         l, volume, plane));
  }
}

namespace {

//! The rim's in-plane displacements δ_b n̂_b (zero off the rim) with the pressure `interior`.
VertexVectors rim_displacements(const Mesh& mesh, const VertexVectors& positions, const FlowOperators& operators,
                                const SubstrateOptions& substrate, double tau, const InteriorPressure& interior)
{
  const double cos_young = std::cos(substrate.contact_angle * std::numbers::pi / 180), mobility = substrate.mobility;
  VertexVectors displacement = VertexVectors::Zero(positions.rows(), 3);
  for (const ContactPoint& p : contact_points(mesh, positions, operators, substrate.z)) {
    const double drive = cos_young - contact_angle_cosine(p, interior);
    double delta = 0;
    if (std::isinf(mobility))
      delta = p.stiffness > 0 ? drive / p.stiffness : 0.0;
    else
      delta = tau * mobility * drive / (1 + tau * mobility * p.stiffness);
    displacement.row(p.vertex) = delta * p.outward.transpose();
  }
  return displacement;
}

} // namespace

VertexVectors contact_line_displacements(const Mesh& mesh, const VertexVectors& positions,
                                         const FlowOperators& operators, const SubstrateOptions& substrate, double tau)
{
  return rim_displacements(mesh, positions, operators, substrate, tau, interior_pressure(mesh, positions, operators));
}

std::vector<double> contact_angle_cosines(const Mesh& mesh, const VertexVectors& positions,
                                          const FlowOperators& operators, double substrate_z)
{
  const InteriorPressure interior = interior_pressure(mesh, positions, operators);
  std::vector<double> cosines;
  for (const ContactPoint& p : contact_points(mesh, positions, operators, substrate_z))
    cosines.push_back(contact_angle_cosine(p, interior));
  return cosines;
}

double SubstrateBoundary::tau_limit(const Mesh& mesh, const FlowOperators& operators) const
{
  if (std::isinf(options_.mobility))
    return std::numeric_limits<double>::infinity();
  const VertexVectors x = vertex_positions(mesh);
  double stiffest = 0;
  for (const ContactPoint& p : contact_points(mesh, x, operators, options_.z))
    stiffest = std::max(stiffest, p.stiffness);
  return stiffest > 0 ? 1 / (options_.mobility * stiffest) : std::numeric_limits<double>::infinity();
}

double SubstrateBoundary::energy(const Mesh& mesh, const VertexVectors& positions) const
{
  // A loop runs clockwise seen from above round the film (against its faces), counter-clockwise
  // round a hole: minus the shoelace sum over the boundary halfedges is the base area.
  double twice_area = 0;
  for (const auto h : mesh.halfedges())
    if (mesh.is_boundary(h)) {
      const int a = mesh.from_vertex_handle(h).idx(), b = mesh.to_vertex_handle(h).idx();
      twice_area -= positions(a, 0) * positions(b, 1) - positions(b, 0) * positions(a, 1);
    }
  return -std::cos(options_.contact_angle * std::numbers::pi / 180) * 0.5 * twice_area;
}

void SubstrateBoundary::move_rim(const Mesh& mesh, const FlowOperators& operators, double tau,
                                 VertexVectors& positions) const
{
  if (!positions.allFinite())
    return; // the trial is rejected as it stands
  int count = 0;
  const std::vector<int> component = face_component_ids(mesh, &count);
  // One pressure for the rim's law and the offset below: the offset then changes E_h by λ times the
  // volume it gives back, which the rim's angle already counted, so the two together lower W_h.
  const InteriorPressure interior = interior_pressure(mesh, positions, operators, component, count);
  const VertexVectors displacement = rim_displacements(mesh, positions, operators, options_, tau, interior);
  const FaceIndices faces = face_indices(mesh);
  const std::vector<BoundaryLoop> loops = boundary_loop_vertices(mesh, component);
  if (loops.empty())
    return;
  const std::vector<double> before = material_volumes(positions, faces, component, count, loops);
  for (const BoundaryLoop& loop : loops)
    for (const int v : loop.vertices) { // x and y only: the contact line's z stays bit for bit
      positions(v, 0) += displacement(v, 0);
      positions(v, 1) += displacement(v, 1);
    }
  const std::vector<double> after = material_volumes(positions, faces, component, count, loops);
  // The volume the rim swept, given back by one normal offset c of each component's interior, at
  // the rate Σ_v ∂V/∂x_v·N_v of the pressure's denominator.
  for (Eigen::Index v = 0; v < positions.rows(); ++v) {
    const int k = interior.component[static_cast<std::size_t>(v)];
    const double rate = k < 0 ? 0.0 : interior.offset_rate[static_cast<std::size_t>(k)];
    if (mesh.is_boundary(Mesh::VertexHandle(static_cast<int>(v))) || !(std::abs(rate) > 0))
      continue;
    const double offset = (before[static_cast<std::size_t>(k)] - after[static_cast<std::size_t>(k)]) / rate;
    positions.row(v) += offset * operators.normals.row(v);
  }
}

RetriangulationHook SubstrateBoundary::rim_topology_hook(RetriangulationHook hook,
                                                         const RetriangulationSchedule& schedule) const
{
  return substrate_topology_hook(std::move(hook), options_.z, schedule);
}

} // namespace sdflow
