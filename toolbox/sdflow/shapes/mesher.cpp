#include "sdflow/shapes/mesher.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/quality.h"
#include "sdflow/log.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/shapes/marching_tetrahedra.h"
#include "sdflow/spatial/intersect.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace sdflow {
namespace {

//! Vertices per area × ℓ² of the remeshed surfaces (measured: 1.07–1.09 on spheres, ellipsoids,
//! tori and the paper's unions; ideal equilateral triangles would give 2/√3 ≈ 1.15).
constexpr double kVerticesPerScaledArea = 1.08;
//! Stop adjusting ℓ once the vertex count is this close to the request.
constexpr double kVertexCountTolerance = 0.02;
constexpr int kMaxVertexCountRounds = 6;
//! Marching cells near the surface are this many target edge lengths: the remesher splits the
//! coarse triangles cheaply, while a finer grid leaves it many more edges to collapse. Where the
//! surface is complex, the octree refines further (marching_tetrahedra.h).
constexpr double kGridCellPerEdge = 2;
//! Grid spacing when the surface declares no feature size and no ℓ is known yet: a fraction of
//! the box diagonal.
constexpr double kDefaultGridFraction = 1.0 / 64;

//! Halvings of the marching grid tried until two successive grids give the same topology, and
//! the finest grid tried, in target edge lengths: finer grids cost memory (a 20-sphere union
//! with sharp creases took 3 GB at ℓ/8) and the remeshing to ℓ could not keep what they find.
constexpr int kMaxGridHalvings = 3;
constexpr double kFinestGridPerEdge = 0.25;

std::string describe(const TopologyCount& t)
{
  return fmt::format("{} component(s), genus {}, {} boundary loop(s)", t.components, t.genus, t.boundary_loops);
}

//! A point of each of the first intersecting pairs, for a message.
std::string crossing_places(const Mesh& mesh, const std::vector<FacePair>& pairs)
{
  std::string text;
  for (std::size_t i = 0; i < std::min<std::size_t>(pairs.size(), 3); ++i) {
    const Eigen::Vector3d c = to_eigen(mesh.calc_face_centroid(mesh.face_handle(pairs[i].first)));
    text += fmt::format("{}({:.4g}, {:.4g}, {:.4g})", i > 0 ? ", " : "", c.x(), c.y(), c.z());
  }
  return text;
}

bool has_boundary(const Mesh& mesh)
{
  for (auto h : mesh.halfedges())
    if (h.is_boundary())
      return true;
  return false;
}

//! The box as a clipping function (≤ 0 inside), for surfaces that leave their box.
ScalarField box_clip(const Eigen::AlignedBox3d& box)
{
  const Eigen::Vector3d centre = box.center(), half = 0.5 * box.sizes();
  return [centre, half](const Eigen::Vector3d& p) { return ((p - centre).cwiseAbs() - half).maxCoeff(); };
}

std::string box_text(const Eigen::AlignedBox3d& b)
{
  return fmt::format("[{:.6g}, {:.6g}] x [{:.6g}, {:.6g}] x [{:.6g}, {:.6g}]", b.min().x(), b.max().x(), b.min().y(),
                     b.max().y(), b.min().z(), b.max().z());
}

//! Marching tetrahedra and clipping (a surface that leaves its box is clipped by it from then on).
Mesh marched_triangulation(ImplicitSurface& surface, double cell)
{
  Mesh mesh = marching_tetrahedra(surface, {.cell_size = cell});
  if (mesh.n_faces() == 0)
    throw InvalidParameter(fmt::format("the level set f = 0 of '{}' is empty in the box {} (no sign change of f on "
                                       "a grid of spacing {:.3g}; enlarge the box or refine the grid)",
                                       surface.name, box_text(surface.box), cell));
  if (!surface.clipped() && has_boundary(mesh)) {
    logger().warn("the surface '{}' leaves its box {}: clipping it by the box", surface.name, box_text(surface.box));
    surface.clip = box_clip(surface.box);
  }
  if (surface.clipped()) {
    mesh = clip_mesh(mesh, surface.clip);
    if (mesh.n_faces() == 0)
      throw InvalidParameter(fmt::format("no part of the level set f = 0 of '{}' lies in its clipping region",
                                         surface.name));
  }
  return mesh;
}

//! Marching tetrahedra, clipping, and projection of every vertex onto the surface or its rim.
Mesh initial_triangulation(ImplicitSurface& surface, double cell, const ProjectionOptions& projection)
{
  Mesh mesh = marched_triangulation(surface, cell);
  for (auto v : mesh.vertices()) {
    const Eigen::Vector3d p = to_eigen(mesh.point(v));
    mesh.set_point(v, to_point(mesh.is_boundary(v) ? project_to_boundary_curve(surface, p, projection)
                                                   : project_to_level_set(surface, p, projection)));
  }
  return mesh;
}

//! InvalidParameter for options mesh_implicit_surface cannot take (mesher.h's MesherOptions).
void check_mesher_input(const ImplicitSurface& input, const MesherOptions& options)
{
  if (!input.value)
    throw InvalidParameter(fmt::format("mesher: surface '{}' has no function", input.name));
  if (input.box.isEmpty() || !(input.box.sizes().array() > 0).all())
    throw InvalidParameter(fmt::format("mesher: the box {} of '{}' is empty", box_text(input.box), input.name));
  const bool by_length = options.edge_length > 0, by_count = options.vertices > 0;
  if (by_length == by_count)
    throw InvalidParameter(fmt::format("mesher: give exactly one of an edge length (got {}) and a vertex count (got {})",
                                       options.edge_length, options.vertices));
  if (by_count && options.vertices < 12)
    throw InvalidParameter(fmt::format("mesher: {} vertices are too few for a surface (at least 12)", options.vertices));
  if (!(options.edges_per_radius >= 0) || !std::isfinite(options.edges_per_radius))
    throw InvalidParameter(fmt::format("mesher: edges per radius must be ≥ 0, got {}", options.edges_per_radius));
  if (!std::isfinite(options.edge_length) || !(options.grid_cell >= 0) || options.iterations < 1 ||
      !(options.tolerance > 0 && options.tolerance < 1e-6))
    throw InvalidParameter(fmt::format("mesher: need finite ℓ, grid cell ≥ 0 (got {}), iterations ≥ 1 (got {}) and a "
                                       "relative tolerance in (0, 1e-6) (got {})",
                                       options.grid_cell, options.iterations, options.tolerance));
}

//! The first triangulation (initial_triangulation) and the ℓ to remesh it to: options.edge_length,
//! or from a vertex count ℓ = √(c A / N), the area A measured on a first triangulation, c
//! calibrated on remeshed surfaces (kVerticesPerScaledArea), the grid refined if ℓ asks for it.
//! Sets result.grid_cell; `surface` is clipped from then on if it leaves its box.
struct FirstTriangulation {
  Mesh mesh;
  double edge_length = 0;
};

FirstTriangulation first_triangulation(ImplicitSurface& surface, const MesherOptions& options,
                                       const ProjectionOptions& projection, MesherResult& result)
{
  const double feature_cell = surface.feature_size > 0 ? surface.feature_size / 2 : surface.scale() * kDefaultGridFraction;
  FirstTriangulation first{.edge_length = options.edge_length};
  const double ell = options.edge_length;
  if (options.edge_length > 0) {
    result.grid_cell = options.grid_cell > 0 ? options.grid_cell : std::min(kGridCellPerEdge * ell, feature_cell);
    first.mesh = initial_triangulation(surface, result.grid_cell, projection);
    return first;
  }
  result.grid_cell = options.grid_cell > 0 ? options.grid_cell : feature_cell;
  ImplicitSurface probe = surface;
  first.mesh = initial_triangulation(probe, result.grid_cell, projection);
  first.edge_length = std::sqrt(kVerticesPerScaledArea * surface_area(first.mesh) / options.vertices);
  if (options.grid_cell == 0 && kGridCellPerEdge * first.edge_length < result.grid_cell) {
    result.grid_cell = kGridCellPerEdge * first.edge_length;
    first.mesh = initial_triangulation(surface, result.grid_cell, projection);
  } else {
    surface = probe;
  }
  return first;
}

//! A grid too coarse for a neck or gap joins or cuts the sheets there, at any orientation of the
//! shape: `mesh` is re-triangulated on grids halved (result.grid_cell) until halving no longer
//! changes its topology, which is then trusted; InvalidParameter when it keeps changing down to
//! kMaxGridHalvings or kFinestGridPerEdge · ℓ.
void refine_grid_until_topology_holds(ImplicitSurface& surface, double ell, const ProjectionOptions& projection,
                                      Mesh& mesh, MesherResult& result)
{
  TopologyCount coarse = count_topology(mesh);
  for (int halving = 0;; ++halving) {
    // The topology is the marching grid's: the projection, the costly part, moves no edge.
    ImplicitSurface finer_surface = surface;
    const TopologyCount fine = count_topology(marched_triangulation(finer_surface, result.grid_cell / 2));
    if (fine == coarse)
      return;
    if (halving == kMaxGridHalvings || result.grid_cell / 4 < kFinestGridPerEdge * ell)
      throw InvalidParameter(fmt::format(
          "mesher: the topology of '{}' keeps changing as the marching grid is refined ({} at spacing {:.3g}, {} "
          "at {:.3g}): a neck or gap thinner than the grid resolves; give the shape's smallest feature "
          "(--feature-size) or a finer --grid-cell",
          surface.name, describe(coarse), result.grid_cell, describe(fine), result.grid_cell / 2));
    logger().info("mesher: '{}' on a grid of spacing {:.3g} has {}, on one of {:.3g} {}: refining the grid",
                  surface.name, result.grid_cell, describe(coarse), result.grid_cell / 2, describe(fine));
    surface = std::move(finer_surface);
    result.grid_cell /= 2;
    mesh = initial_triangulation(surface, result.grid_cell, projection);
    coarse = fine;
  }
}

//! `mesh` remeshed to ℓ onto the level set (remesh: its projections), and for a vertex count again
//! with ℓ scaled by √(vertices / requested) until within kVertexCountTolerance of it, at most
//! kMaxVertexCountRounds rounds. Returns the ℓ last used.
double remesh_to_target(Mesh& mesh, double ell, const MesherOptions& options, RemeshOptions& remesh,
                        MesherResult& result)
{
  for (int round = 0;; ++round) {
    remesh.edge_length = ell;
    remesh.iterations = round == 0 ? options.iterations : std::max(3, options.iterations / 2);
    auto remeshed = isotropic_remesh(mesh, remesh);
    mesh = std::move(remeshed.mesh);
    result.remesh = remeshed.statistics;
    result.remesh_rounds = round + 1;
    if (options.vertices <= 0 || round + 1 == kMaxVertexCountRounds)
      return ell;
    const double ratio = static_cast<double>(mesh.n_vertices()) / options.vertices;
    if (std::abs(ratio - 1) <= kVertexCountTolerance)
      return ell;
    ell *= std::sqrt(ratio); // vertex count scales like ℓ⁻²
  }
}

//! `mesh` refined where it curves (radius_targets, down to ℓ/4), twice: the second pass sees the
//! curvature of the refined mesh.
void refine_by_curvature(Mesh& mesh, double ell, const MesherOptions& options, RemeshOptions& remesh,
                         MesherResult& result)
{
  for (int pass = 0; pass < 2; ++pass) {
    Mesh clean = mesh;
    clean.garbage_collection();
    remesh.sizing = nearest_vertex_sizing(
        clean, radius_targets(clean, {.edges_per_radius = options.edges_per_radius, .min_length = ell / 4,
                                      .max_length = ell}));
    remesh.iterations = std::max(3, options.iterations / 2);
    auto remeshed = isotropic_remesh(clean, remesh);
    mesh = std::move(remeshed.mesh);
    result.remesh = remeshed.statistics;
  }
}

//! The largest distances of `mesh`'s vertices from the level set and of its rim from the clipping
//! surface, relative to the surface's scale (MesherResult).
void measure_distances(const ImplicitSurface& surface, const Mesh& mesh, MesherResult& result)
{
  const double scale = surface.scale();
  for (auto v : mesh.vertices()) {
    const Eigen::Vector3d p = to_eigen(mesh.point(v));
    result.max_level_set_distance = std::max(result.max_level_set_distance, level_set_distance(surface, p) / scale);
    if (mesh.is_boundary(v) && surface.clipped()) {
      const double g = std::abs(surface.clip(p)) / clip_gradient(surface, p).norm();
      result.max_boundary_distance = std::max(result.max_boundary_distance, g / scale);
    }
  }
}

//! InvalidParameter when the remeshing to ℓ changed the marched topology or left the surface
//! crossing itself (MesherOptions::check_topology).
void check_remeshed_topology(const ImplicitSurface& surface, double ell, const TopologyCount& marched, Mesh& mesh)
{
  collect_garbage(mesh);
  const TopologyCount remeshed = count_topology(mesh);
  if (remeshed != marched)
    throw InvalidParameter(fmt::format("mesher: remeshing '{}' to ℓ = {:.4g} changed its topology ({} → {}): a "
                                       "neck, gap or crease narrower than ℓ; give a smaller edge length or a blend",
                                       surface.name, ell, describe(marched), describe(remeshed)));
  const std::vector<FacePair> pairs = self_intersections(mesh);
  if (!pairs.empty())
    throw InvalidParameter(fmt::format("mesher: the triangulation of '{}' at ℓ = {:.4g} crosses itself ({} face "
                                       "pairs, near {}): a crease or gap narrower than ℓ; give a smaller edge "
                                       "length or a blend",
                                       surface.name, ell, pairs.size(), crossing_places(mesh, pairs)));
}

} // namespace

AngleDistribution triangle_min_angle_distribution(const Mesh& mesh)
{
  AngleDistribution d;
  std::vector<double> angles;
  angles.reserve(mesh.n_faces());
  for (auto f : mesh.faces())
    angles.push_back(smallest_angle_deg(mesh, f));
  if (angles.empty())
    return d;
  std::sort(angles.begin(), angles.end());
  const auto at = [&](double q) { return angles[static_cast<std::size_t>(q * (angles.size() - 1))]; };
  d.min = angles.front();
  d.p01 = at(0.01);
  d.p05 = at(0.05);
  d.p25 = at(0.25);
  d.median = at(0.5);
  double sum = 0;
  for (double a : angles) {
    sum += a;
    ++d.histogram[std::min<std::size_t>(static_cast<std::size_t>(a / 10), d.histogram.size() - 1)];
  }
  d.mean = sum / angles.size();
  return d;
}

MesherResult mesh_implicit_surface(const ImplicitSurface& input, const MesherOptions& options)
{
  check_mesher_input(input, options);
  ImplicitSurface surface = input;
  const ProjectionOptions projection{.tolerance = options.tolerance};
  MesherResult result;
  FirstTriangulation first = first_triangulation(surface, options, projection, result);
  Mesh mesh = std::move(first.mesh);
  double ell = first.edge_length;
  if (options.check_topology)
    refine_grid_until_topology_holds(surface, ell, projection, mesh, result);
  result.initial_vertices = mesh.n_vertices();
  result.initial_faces = mesh.n_faces();
  const TopologyCount marched = count_topology(mesh);
  logger().debug("mesher: '{}' marching grid {:.4g}: {} vertices, {} faces", surface.name, result.grid_cell,
                 mesh.n_vertices(), mesh.n_faces());

  RemeshOptions remesh{
      .edge_length = ell,
      .iterations = options.iterations,
      .project = [&](const Eigen::Vector3d& p) { return project_to_level_set(surface, p, projection); },
      .project_boundary = [&](const Eigen::Vector3d& p) { return project_to_boundary_curve(surface, p, projection); },
      .boundary = BoundaryMode::remesh,
      .boundary_corner_angle_deg = 45,
      .sizing = {},
  };
  if (!surface.clipped())
    remesh.project_boundary = remesh.project; // no boundary exists; never called
  ell = remesh_to_target(mesh, ell, options, remesh, result);
  result.edge_length = ell;
  if (options.edges_per_radius > 0)
    refine_by_curvature(mesh, ell, options, remesh, result);

  measure_distances(surface, mesh, result);
  result.min_angles = triangle_min_angle_distribution(mesh);
  if (options.check_topology)
    check_remeshed_topology(surface, ell, marched, mesh);
  result.mesh = std::move(mesh);
  logger().info("mesher: '{}' → {} vertices, {} faces at ℓ = {:.4g}; min angle {:.1f}°, 5th percentile {:.1f}°",
                surface.name, result.mesh.n_vertices(), result.mesh.n_faces(), ell, result.min_angles.min,
                result.min_angles.p05);
  return result;
}

} // namespace sdflow
