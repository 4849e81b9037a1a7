#include "sdflow/flow/scheme.h"

#include "sdflow/errors.h"
#include "sdflow/flow/anisotropic_energy.h"
#include "sdflow/flow/isotropic_energy.h"
#include "sdflow/flow/willmore_energy.h"
#include "sdflow/stopwatch.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace sdflow {

double flow_energy(const SchemeParts& parts, const Mesh& mesh, const VertexVectors& positions)
{
  return parts.energy->value_at(mesh, positions) + parts.boundary->energy(mesh, positions);
}

SchemeParts scheme_parts(const SchemeOptions& options)
{
  std::shared_ptr<const SurfaceEnergy> energy;
  std::shared_ptr<const Anisotropy> anisotropy;
  if (options.energy.kind == SurfaceEnergyKind::isotropic) {
    energy = std::make_shared<const IsotropicEnergy>(options.curvature);
  } else {
    anisotropy = make_anisotropy(options.energy);
    energy = std::make_shared<const AnisotropicEnergy>(anisotropy);
  }
  if (options.energy.willmore != 0)
    energy = std::make_shared<const WillmoreRegularisedEnergy>(std::move(energy), options.energy.willmore);
  return {std::move(energy), flow_boundary(options.boundary, options.substrate), std::move(anisotropy)};
}

FlowOperators flow_operators(const Mesh& mesh, const SchemeOptions& options, const CotangentCache* cache)
{
  return flow_operators(mesh, options, scheme_parts(options), cache);
}

FlowOperators flow_operators(const Mesh& mesh, const SchemeOptions& options, const SchemeParts& parts,
                             const CotangentCache* cache)
{
  if (!(options.beta >= 0) || !std::isfinite(options.beta))
    throw InvalidParameter(fmt::format("flow step: β must be finite and ≥ 0, got {}", options.beta));
  if (mesh.n_vertices() == 0 || mesh.n_faces() == 0)
    throw InvalidMesh("flow step: the mesh has no triangles");
  FlowOperators op;
  op.parts = parts;
  if (cache) {
    cache->assemble(mesh, op.laplacian, op.areas); // checks that the cache fits the mesh
    op.normals = vertex_normals(mesh, cache->triangles(), options.normals);
  } else {
    op.normals = vertex_normals(mesh, options.normals);
    op.laplacian = cotangent_laplacian(mesh);
    op.areas = mixed_voronoi_areas(mesh);
  }
  for (Eigen::Index i = 0; i < op.areas.size(); ++i)
    if (!(op.areas[i] > 0))
      throw InvalidMesh(fmt::format("flow step: vertex {} has no area {} (isolated or degenerate star)", i,
                                    op.areas[i]));
  if (options.mass == VertexMass::volume_gradient) {
    // A star folded over itself sweeps little or negative volume: there the Voronoi area stands in.
    const Eigen::VectorXd gradient = volume_gradient_areas(mesh, op.normals);
    for (Eigen::Index i = 0; i < gradient.size(); ++i) {
      if (gradient[i] > kMassFallbackFraction * op.areas[i])
        op.areas[i] = gradient[i];
      else
        ++op.mass_fallbacks;
    }
  }
  op.curvature = parts.energy->first_variation({mesh, op.normals, op.laplacian, op.areas});
  parts.boundary->impose(mesh, op.laplacian, op.curvature, op.held);
  op.rhs = op.laplacian * op.curvature;
  op.tau_limit = parts.boundary->tau_limit(mesh, op);
  return op;
}

std::array<Eigen::VectorXd, 2> warm_starts(const Eigen::VectorXd& last_w, const Eigen::VectorXd& earlier_w)
{
  if (last_w.size() == 0 || earlier_w.size() != last_w.size())
    return {last_w, Eigen::VectorXd()};
  return {last_w, 2 * last_w - earlier_w};
}

StepResult solve_step(const Mesh& mesh, const FlowOperators& op, double tau, double beta, FlowSolver& solver,
                      std::span<const Eigen::VectorXd> guesses)
{
  if (!(tau > 0) || !std::isfinite(tau))
    throw InvalidParameter(fmt::format("flow step: τ must be finite and positive, got {}", tau));
  StepResult result;
  result.w = solver.solve(op.system(tau * beta), op.rhs, guesses, &result.solve);
  result.positions = vertex_positions(mesh);
  if (result.solve.factorised) {
    result.factorisations = 1;
    result.factorised_positions = result.positions;
    result.factorised_tau_beta = tau * beta;
  }
  result.positions -= (tau * result.w).asDiagonal() * op.normals;
  op.parts.boundary->move_rim(mesh, op, tau, result.positions);
  return result;
}

StepResult extrapolated_step(const Mesh& mesh, const FlowOperators& op, double tau, const SchemeOptions& options,
                             FlowSolver& solver, FlowSolver& half_solver, const CotangentCache* cache,
                             std::span<const Eigen::VectorXd> guesses)
{
  StepResult result = solve_step(mesh, op, tau, options.beta, solver, guesses);
  const auto absorb = [&result](const StepResult& half) {
    result.solve.analysed |= half.solve.analysed;
    result.solve.iterations += half.solve.iterations;
    result.solve.relative_residual = std::max(result.solve.relative_residual, half.solve.relative_residual);
    result.factorisations += half.factorisations;
    result.solve.seconds.assembly += half.solve.seconds.assembly;
    result.solve.seconds.factorisation += half.solve.seconds.factorisation;
    result.solve.seconds.solve += half.solve.seconds.solve;
    if (half.solve.factorised) {
      result.half_factorised = true;
      result.half_factorised_positions = half.factorised_positions;
      result.half_factorised_tau_beta = half.factorised_tau_beta;
    }
  };
  const StepResult first_half = solve_step(mesh, op, tau / 2, options.beta, half_solver, {&result.w, 1});
  absorb(first_half);
  Mesh halfway = mesh;
  set_vertex_positions(halfway, first_half.positions);
  const Stopwatch watch;
  const FlowOperators halfway_operators = flow_operators(halfway, options, op.parts, cache);
  result.operators_seconds = watch.seconds();
  const StepResult second_half =
      solve_step(halfway, halfway_operators, tau / 2, options.beta, half_solver, {&first_half.w, 1});
  absorb(second_half);
  result.error = second_half.positions - result.positions;
  result.positions = second_half.positions + result.error;
  result.w = first_half.w + second_half.w - result.w;
  return result;
}

StepResult flow_step(const Mesh& mesh, double tau, const SchemeOptions& options, const SolverOptions& solver_options)
{
  FlowSolver solver(solver_options), half_solver(solver_options);
  const FlowOperators operators = flow_operators(mesh, options);
  return options.extrapolate ? extrapolated_step(mesh, operators, tau, options, solver, half_solver)
                             : solve_step(mesh, operators, tau, options.beta, solver);
}

} // namespace sdflow
