#include "sdflow/retri/surface_union.h"

#include "sdflow/errors.h"
#include "sdflow/retri/corefine.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/io/validate.h"
#include "sdflow/log.h"
#include "sdflow/spatial/bvh.h"
#include "sdflow/spatial/intersect.h"

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <tuple>
#include <vector>

namespace sdflow {
namespace {

//! The triangles of a mesh as sets of corner coordinates, each rotated to start at its smallest
//! corner (the orientation is kept), sorted: equal for two meshes of the same surface.
std::vector<std::array<Eigen::Vector3d, 3>> triangle_set(const Mesh& mesh)
{
  const auto less = [](const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
    return std::lexicographical_compare(p.data(), p.data() + 3, q.data(), q.data() + 3);
  };
  std::vector<std::array<Eigen::Vector3d, 3>> set;
  set.reserve(mesh.n_faces());
  for (auto f : mesh.faces()) {
    std::array<Eigen::Vector3d, 3> t;
    int k = 0;
    for (auto v : f.vertices())
      t[k++] = to_eigen(mesh.point(v));
    const auto first = std::min_element(t.begin(), t.end(), less);
    std::rotate(t.begin(), first, t.end());
    set.push_back(t);
  }
  std::sort(set.begin(), set.end(), [&](const auto& s, const auto& t) {
    return std::lexicographical_compare(s.begin(), s.end(), t.begin(), t.end(), less);
  });
  return set;
}

bool same_triangles(const Mesh& a, const Mesh& b)
{
  return a.n_faces() == b.n_faces() && a.n_faces() > 0 && triangle_set(a) == triangle_set(b);
}

//! Side of a surface through the angle-weighted pseudonormal at the closest point (Bærentzen &
//! Aanæs 2005): exact sign for closed surfaces, whether the closest point is inside a face, on an
//! edge or at a vertex.
class SideOracle {
public:
  explicit SideOracle(const Mesh& mesh) : mesh_(mesh), bvh_(mesh)
  {
    face_normal_.resize(mesh.n_faces());
    vertex_normal_.assign(mesh.n_vertices(), Eigen::Vector3d::Zero());
    for (auto f : mesh.faces()) {
      face_normal_[f.idx()] = to_eigen(mesh.calc_face_normal(f));
      for (auto h : f.halfedges())
        vertex_normal_[h.to().idx()] += mesh.calc_sector_angle(h) * face_normal_[f.idx()];
    }
  }

  struct Side {
    bool inside = false;
    double distance = std::numeric_limits<double>::infinity();
    int face = -1; //!< the face of the closest point
  };

  //! Whether q lies inside the surface, and its distance to it.
  Side side(const Eigen::Vector3d& q) const
  {
    const ClosestPoint cp = bvh_.closest_point(q);
    if (cp.face < 0)
      return {};
    const Mesh::FaceHandle f(cp.face);
    constexpr double on_element = 1e-10;
    int zeros = 0, nonzero = -1;
    for (int k = 0; k < 3; ++k) {
      if (cp.barycentric[k] < on_element)
        ++zeros;
      else
        nonzero = k;
    }
    Eigen::Vector3d normal = face_normal_[cp.face];
    const auto corners = bvh_.triangle(cp.face);
    if (zeros == 2) {
      normal = vertex_normal_[corners[nonzero]];
    } else if (zeros == 1) {
      // On the edge opposite the zero weight: add the neighbour across it.
      for (auto h : mesh_.fh_range(f)) {
        const int from = h.from().idx(), to = h.to().idx();
        bool opposite_zero = true;
        for (int k = 0; k < 3; ++k)
          if ((corners[k] == from || corners[k] == to) && cp.barycentric[k] < on_element)
            opposite_zero = false;
        if (opposite_zero && !h.opp().is_boundary()) {
          normal += face_normal_[h.opp().face().idx()];
          break;
        }
      }
    }
    return {.inside = (q - cp.point).dot(normal) < 0, .distance = std::sqrt(cp.squared_distance), .face = cp.face};
  }

private:
  const Mesh& mesh_;
  Bvh bvh_;
  std::vector<Eigen::Vector3d> face_normal_;
  std::vector<Eigen::Vector3d> vertex_normal_;
};

//! Delete the faces flagged in `remove`, then faces around vertices left with several boundary
//! gaps (a loop through them would be a figure eight), until every vertex is manifold.
int remove_faces(Mesh& mesh, std::vector<bool> remove)
{
  int removed = 0;
  for (bool changed = true; changed;) {
    changed = false;
    for (auto f : mesh.faces())
      if (remove[f.idx()]) {
        mesh.delete_face(f, true);
        ++removed;
        changed = true;
      }
    std::fill(remove.begin(), remove.end(), false);
    for (auto v : mesh.vertices()) {
      int gaps = 0;
      for (auto h : v.outgoing_halfedges())
        gaps += h.is_boundary();
      if (gaps > 1)
        for (auto f : v.faces())
          remove[f.idx()] = true;
    }
  }
  return removed;
}

struct Loop {
  std::vector<Eigen::Vector3d> points;
  std::vector<int> vertices; //!< indices in the combined vertex list
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
};

//! Boundary loops of `mesh` in boundary-halfedge order, vertex indices shifted by `offset`.
std::vector<Loop> loops_of(const Mesh& mesh, int offset)
{
  std::vector<Loop> loops;
  for (const std::vector<Mesh::HalfedgeHandle>& halfedges : boundary_loops(mesh)) {
    Loop loop;
    for (const auto g : halfedges) {
      const auto from = mesh.from_vertex_handle(g);
      loop.points.push_back(to_eigen(mesh.point(from)));
      loop.vertices.push_back(from.idx() + offset);
      loop.centre += loop.points.back();
    }
    loop.centre /= static_cast<double>(loop.points.size());
    loops.push_back(std::move(loop));
  }
  return loops;
}

//! Triangulate the band between loop a (in its boundary order) and loop b (walked against its
//! boundary order, so both run the same way in space), always adding the shorter new rung
//! (Christiansen & Sederberg 1978 contour tiling), unless that rung's triangle has zero area.
void bridge(const Loop& a, const Loop& b, std::vector<std::array<int, 3>>& faces)
{
  const int na = static_cast<int>(a.points.size()), nb = static_cast<int>(b.points.size());
  int start_b = 0;
  double best = std::numeric_limits<double>::infinity();
  for (int j = 0; j < nb; ++j)
    if (const double d = (b.points[j] - a.points[0]).squaredNorm(); d < best) {
      best = d;
      start_b = j;
    }
  // b walked backwards: position k ↦ index start_b - k.
  auto b_at = [&](int k) { return ((start_b - k) % nb + nb) % nb; };
  const double zero_area = BuildOptions{}.zero_area_tolerance;
  for (int i = 0, k = 0; i < na || k < nb;) {
    bool advance_a = k == nb || (i < na && (a.points[(i + 1) % na] - b.points[b_at(k)]).squaredNorm() <=
                                               (a.points[i % na] - b.points[b_at(k + 1)]).squaredNorm());
    // Never a zero-area triangle (validation's test) where the other rung makes a proper one.
    if (i < na && k < nb) {
      const bool a_flat = has_zero_area(a.points[i % na], a.points[(i + 1) % na], b.points[b_at(k)], zero_area);
      const bool b_flat = has_zero_area(b.points[b_at(k + 1)], b.points[b_at(k)], a.points[i % na], zero_area);
      if (a_flat != b_flat)
        advance_a = b_flat;
    }
    if (advance_a) {
      faces.push_back({a.vertices[i % na], a.vertices[(i + 1) % na], b.vertices[b_at(k)]});
      ++i;
    } else {
      faces.push_back({b.vertices[b_at(k + 1)], b.vertices[b_at(k)], a.vertices[i % na]});
      ++k;
    }
  }
}

void append(const Mesh& mesh, VertexVectors& x, std::vector<std::array<int, 3>>& faces, int offset)
{
  for (auto v : mesh.vertices())
    x.row(offset + v.idx()) = to_eigen(mesh.point(v)).transpose();
  for (auto f : mesh.faces()) {
    std::array<int, 3> t{};
    int k = 0;
    for (auto v : f.vertices())
      t[k++] = v.idx() + offset;
    faces.push_back(t);
  }
}

//! The mesh with unreferenced vertices dropped.
Mesh compact(const VertexVectors& x, const std::vector<std::array<int, 3>>& faces)
{
  std::vector<int> number(x.rows(), -1);
  int used = 0;
  for (const auto& t : faces)
    for (int v : t)
      if (number[v] < 0)
        number[v] = used++;
  VertexVectors y(used, 3);
  for (Eigen::Index v = 0; v < x.rows(); ++v)
    if (number[v] >= 0)
      y.row(number[v]) = x.row(v);
  FaceIndices t(faces.size(), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    t.row(f) << number[faces[f][0]], number[faces[f][1]], number[faces[f][2]];
  return make_mesh(y, t);
}

//! Vertex property: the vertex lay on a boundary loop of the input surface.
const char* const kInputBoundary = "sdflow:union:input_boundary";

//! The boundary loops of `kept` (`input` less the removed faces) that removing faces opened; the
//! loops of the input's own boundary are left out. Throws InvalidMesh when the removal reached an
//! input boundary, which leaves a loop that is part old boundary and part new.
std::vector<Loop> opened_loops(const Mesh& kept, OpenMesh::VPropHandleT<bool> input_boundary, int offset,
                               const char* which)
{
  std::vector<Loop> opened;
  for (Loop& loop : loops_of(kept, offset)) {
    std::size_t on_input_boundary = 0;
    for (const int v : loop.vertices)
      on_input_boundary += kept.property(input_boundary, Mesh::VertexHandle(v - offset));
    if (on_input_boundary == loop.vertices.size())
      continue;
    if (on_input_boundary > 0)
      throw InvalidMesh(fmt::format("surface union: the overlap reaches the boundary of the {} surface ({} of the {} "
                                    "vertices around the cut lie on it): its edge would have to be cut",
                                    which, on_input_boundary, loop.vertices.size()));
    opened.push_back(std::move(loop));
  }
  return opened;
}

//! `mesh` less the faces flagged in `remove` (and those remove_faces adds), garbage-collected, its
//! vertices marked by whether they lay on the input's boundary. Returns the faces removed.
int keep_faces(Mesh& mesh, const std::vector<bool>& remove, OpenMesh::VPropHandleT<bool>& input_boundary)
{
  mesh.add_property(input_boundary, kInputBoundary);
  for (auto v : mesh.vertices())
    mesh.property(input_boundary, v) = v.is_boundary();
  const int removed = remove_faces(mesh, remove);
  mesh.garbage_collection();
  return removed;
}

//! Per face of one surface, seen from the other: crossing it, inside it (by the centroid;
//! SideOracle), and closer to it than the longer of the longest edges of the face and of the
//! other's face nearest to it (the same reach from both sides, so that the holes match).
struct FacesAgainst {
  std::vector<bool> crossing, inside, near;
};

std::vector<double> longest_edges(const Mesh& mesh)
{
  std::vector<double> longest(mesh.n_faces(), 0.0);
  for (auto f : mesh.faces())
    for (auto e : f.edges())
      longest[f.idx()] = std::max(longest[f.idx()], mesh.calc_edge_length(e));
  return longest;
}

FacesAgainst faces_against(const Mesh& surface, const std::vector<double>& longest, const SideOracle& other,
                           const std::vector<double>& other_longest)
{
  FacesAgainst r{.crossing = std::vector<bool>(surface.n_faces(), false),
                 .inside = std::vector<bool>(surface.n_faces(), false),
                 .near = std::vector<bool>(surface.n_faces(), false)};
  for (auto f : surface.faces()) {
    const SideOracle::Side side = other.side(to_eigen(surface.calc_face_centroid(f)));
    r.inside[f.idx()] = side.inside;
    r.near[f.idx()] = side.face >= 0 && side.distance < std::max(longest[f.idx()], other_longest[side.face]);
  }
  return r;
}

//! Which faces of each surface cross the other, lie inside it or come close to it.
struct Overlap {
  FacesAgainst a, b;
};

Overlap overlap_of(const Mesh& a, const Mesh& b)
{
  const SideOracle oracle_a(a), oracle_b(b);
  const std::vector<double> longest_a = longest_edges(a), longest_b = longest_edges(b);
  Overlap o{.a = faces_against(a, longest_a, oracle_b, longest_b), .b = faces_against(b, longest_b, oracle_a, longest_a)};
  for (const FacePair& p : surface_intersections(a, b)) {
    o.a.crossing[p.first] = true;
    o.b.crossing[p.second] = true;
  }
  return o;
}

//! The faces to remove: those crossing the other surface, those on the other's inside (its
//! complement when `other_reversed`), and with `near_too` those closer to it than their longest edge.
std::vector<bool> faces_to_remove(const FacesAgainst& faces, bool other_reversed, bool near_too)
{
  std::vector<bool> remove(faces.crossing.size());
  for (std::size_t f = 0; f < remove.size(); ++f)
    remove[f] = faces.crossing[f] || faces.inside[f] != other_reversed || (near_too && faces.near[f]);
  return remove;
}

//! True when every face on the other's inside (its complement when `other_reversed`) lies within
//! an edge of it (FacesAgainst::near): the surfaces have just moved through each other.
bool fresh_contact(const FacesAgainst& faces, bool other_reversed)
{
  for (std::size_t f = 0; f < faces.crossing.size(); ++f)
    if (!faces.crossing[f] && faces.inside[f] != other_reversed && !faces.near[f])
      return false;
  return true;
}

//! The mesh with every triangle's orientation reversed.
Mesh reversed(const Mesh& mesh)
{
  FaceIndices t = face_indices(mesh);
  t.col(1).swap(t.col(2));
  return make_mesh(vertex_positions(mesh), t);
}

//! True when most of `surface`'s area that does not cross the other surface lies on the other's
//! inside.
bool mostly_inside(const Mesh& surface, const FacesAgainst& faces)
{
  double inside = 0, outside = 0;
  for (auto f : surface.faces())
    if (!faces.crossing[f.idx()])
      (faces.inside[f.idx()] ? inside : outside) += surface.calc_face_area(f);
  return inside > outside;
}

//! The surfaces joined by bands (zippering): the faces to remove removed, then one band for each
//! pair of facing loops that the removal opened. merge_touching_surfaces uses it for a joint about an
//! edge wide at a fresh contact, and for surfaces that cross themselves, which corefine cannot split.
UnionResult zipped_joint(const Mesh& a, const Mesh& b, const std::vector<bool>& remove_a, const std::vector<bool>& remove_b)
{
  UnionResult result;
  Mesh kept_a = a, kept_b = b;
  OpenMesh::VPropHandleT<bool> boundary_a, boundary_b;
  result.removed_faces_a = keep_faces(kept_a, remove_a, boundary_a);
  result.removed_faces_b = keep_faces(kept_b, remove_b, boundary_b);

  const int offset = static_cast<int>(kept_a.n_vertices());
  VertexVectors x(kept_a.n_vertices() + kept_b.n_vertices(), 3);
  std::vector<std::array<int, 3>> faces;
  append(kept_a, x, faces, 0);
  append(kept_b, x, faces, offset);

  const std::vector<Loop> loops_a = opened_loops(kept_a, boundary_a, 0, "first"),
                          loops_b = opened_loops(kept_b, boundary_b, offset, "second");
  if (loops_a.size() != loops_b.size()) {
    // One surface wholly inside or across the other, while the other opened: no band can join them.
    for (const auto& [kept, input, removed, name, other] :
         {std::tuple{&kept_a, &a, result.removed_faces_a, "first", "second"},
          std::tuple{&kept_b, &b, result.removed_faces_b, "second", "first"}})
      if (kept->n_faces() == 0 && input->n_faces() > 0)
        throw InvalidMesh(fmt::format("surface union: the bodies overlap so much that no face of the {} surface lies "
                                      "outside the {} (all {} inside it or crossing it): it is meshed too coarsely "
                                      "for their overlap (refine it, `sdflow remesh`), or lies almost wholly inside",
                                      name, other, removed));
    throw InvalidMesh(fmt::format("surface union: the bodies overlap, but removing the overlap left {} boundary "
                                  "loop(s) on the first surface and {} on the second, which cannot be paired: the "
                                  "meshes are too coarse for the curve along which they cross (or the surfaces "
                                  "nearly coincide there); refine them near the contact (`sdflow remesh`)",
                                  loops_a.size(), loops_b.size()));
  }
  std::vector<bool> used(loops_b.size(), false);
  for (const Loop& loop : loops_a) {
    int partner = -1;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < loops_b.size(); ++j)
      if (!used[j] && (loops_b[j].centre - loop.centre).squaredNorm() < best) {
        best = (loops_b[j].centre - loop.centre).squaredNorm();
        partner = static_cast<int>(j);
      }
    used[partner] = true;
    bridge(loop, loops_b[partner], faces);
    ++result.joined_loops;
  }
  if (faces.empty() && a.n_faces() > 0 && b.n_faces() > 0)
    throw InvalidMesh(fmt::format("surface union: the two bodies overlap so much that no face of either lies "
                                  "outside the other ({} + {} faces inside or crossing), so there is no boundary "
                                  "left to join: they are the same body twice, or meshed too coarsely for their "
                                  "overlap (refine them, `sdflow remesh`)",
                                  result.removed_faces_a, result.removed_faces_b));
  try {
    result.mesh = compact(x, faces);
  } catch (const InvalidMesh& e) {
    throw InvalidMesh(fmt::format("surface union: the bodies overlap, but joining the boundary loops their overlap "
                                  "left did not give a manifold surface ({}); refine them near the contact (`sdflow "
                                  "remesh`)",
                                  e.what()));
  }
  logger().debug("surface union: removed {} + {} faces, joined {} loop pair(s)", result.removed_faces_a,
                 result.removed_faces_b, result.joined_loops);
  return result;
}

//! Faces of a split surface grouped into patches, connected across the edges that are not on a
//! crossing curve: each patch lies wholly on one side of the other surface.
std::vector<int> patches_of(const std::vector<std::array<int, 3>>& faces, const std::set<std::array<int, 2>>& curve,
                            int& count)
{
  std::vector<int> parent(faces.size());
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int f) {
    while (parent[f] != f)
      f = parent[f] = parent[parent[f]];
    return f;
  };
  std::map<std::array<int, 2>, int> first_face;
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const std::array<int, 2> edge{std::min(faces[f][k], faces[f][(k + 1) % 3]),
                                    std::max(faces[f][k], faces[f][(k + 1) % 3])};
      if (curve.count(edge) > 0)
        continue;
      if (const auto [at, fresh] = first_face.emplace(edge, static_cast<int>(f)); !fresh)
        parent[root(static_cast<int>(f))] = root(at->second);
    }
  std::vector<int> patch(faces.size());
  std::map<int, int> number;
  for (std::size_t f = 0; f < faces.size(); ++f)
    patch[f] = number.emplace(root(static_cast<int>(f)), static_cast<int>(number.size())).first->second;
  count = static_cast<int>(number.size());
  return patch;
}

//! Whether each patch lies inside `other`, read at the patch's face whose centroid is farthest from
//! it: next to a crossing curve the split faces are slivers whose centroids lie within round-off of
//! the other surface, where the sign says nothing.
std::vector<bool> patches_inside(const VertexVectors& x, const std::vector<std::array<int, 3>>& faces,
                                 const std::vector<int>& patch, int count, const SideOracle& other)
{
  std::vector<SideOracle::Side> farthest(static_cast<std::size_t>(count), SideOracle::Side{.distance = -1});
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const Eigen::Vector3d centroid =
        (x.row(faces[f][0]) + x.row(faces[f][1]) + x.row(faces[f][2])).transpose() / 3;
    const SideOracle::Side side = other.side(centroid);
    auto& best = farthest[static_cast<std::size_t>(patch[f])];
    if (side.distance > best.distance)
      best = side;
  }
  std::vector<bool> inside(static_cast<std::size_t>(count));
  for (std::size_t p = 0; p < inside.size(); ++p)
    inside[p] = farthest[p].inside;
  return inside;
}

//! Number of connected curves among the crossing curves' edges.
int curve_count(const std::vector<std::array<int, 2>>& curve)
{
  std::map<int, int> parent;
  const auto root = [&](int v) {
    parent.emplace(v, v);
    while (parent[v] != v)
      v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const auto& [p, q] : curve)
    parent[root(p)] = root(q);
  std::set<int> roots;
  for (const auto& [v, up] : parent)
    roots.insert(root(v));
  return static_cast<int>(roots.size());
}

//! The surface moved by `shift`.
Mesh translated(const Mesh& mesh, const Eigen::Vector3d& shift)
{
  Mesh moved = mesh;
  for (auto v : moved.vertices())
    moved.set_point(v, to_point(to_eigen(moved.point(v)) + shift));
  return moved;
}

//! corefine(a, b), with b moved by a round-off amount when a and b are not in general position:
//! 10⁻¹², then 10⁻¹⁰ and 10⁻⁸ of the bounding box's diagonal, in a direction of no symmetry.
std::pair<Corefinement, Mesh> corefined(const Mesh& a, const Mesh& b)
{
  const Eigen::Vector3d direction = Eigen::Vector3d(0.5773, 0.3183, 0.7519).normalized();
  Eigen::AlignedBox3d box;
  for (const Mesh* m : {&a, &b})
    for (auto v : m->vertices())
      box.extend(to_eigen(m->point(v)));
  const double diagonal = box.isEmpty() ? 0.0 : box.diagonal().norm();
  try {
    return {corefine(a, b), b};
  } catch (const CorefinementDegenerate& first) {
    for (const double fraction : {1e-12, 1e-10, 1e-8}) {
      const Mesh moved = translated(b, fraction * diagonal * direction);
      try {
        Corefinement c = corefine(a, moved);
        logger().debug("surface union: {}; the second surface moved by {:g} of the diagonal", first.what(), fraction);
        return {std::move(c), moved};
      } catch (const CorefinementDegenerate&) {
      }
    }
    throw InvalidMesh(fmt::format("surface union: {}, even with one surface moved by 10⁻⁸ of the diagonal", first.what()));
  }
}

//! The union's boundary, exactly: both surfaces split along their crossing curves (corefine.h),
//! the patches of each that lie inside the other removed, and what is left joined along the curves,
//! whose vertices both keep.
UnionResult exact_union(const Mesh& a, const Mesh& input_b)
{
  const auto [split, b] = corefined(a, input_b);
  const std::set<std::array<int, 2>> curve(split.curve.begin(), split.curve.end());
  const int offset = static_cast<int>(a.n_vertices());
  std::vector<bool> on_input_boundary(static_cast<std::size_t>(split.points.rows()), false);
  for (const auto& [mesh, shift] : {std::pair{&a, 0}, std::pair{&b, offset}})
    for (auto v : mesh->vertices())
      on_input_boundary[static_cast<std::size_t>(v.idx() + shift)] = v.is_boundary();

  UnionResult result;
  std::vector<std::array<int, 3>> faces;
  for (const auto& [own, other, removed, name] :
       {std::tuple{&split.faces_a, &b, &result.removed_faces_a, "first"},
        std::tuple{&split.faces_b, &a, &result.removed_faces_b, "second"}}) {
    int count = 0;
    const std::vector<int> patch = patches_of(*own, curve, count);
    const std::vector<bool> inside = patches_inside(split.points, *own, patch, count, SideOracle(*other));
    for (std::size_t f = 0; f < own->size(); ++f) {
      if (!inside[static_cast<std::size_t>(patch[f])]) {
        faces.push_back((*own)[f]);
        continue;
      }
      ++*removed;
      for (const int v : (*own)[f])
        if (on_input_boundary[static_cast<std::size_t>(v)])
          throw InvalidMesh(fmt::format("surface union: the overlap reaches the boundary of the {} surface: its edge "
                                        "would have to be cut",
                                        name));
    }
  }
  result.joined_loops = curve_count(split.curve);
  if (faces.empty() && a.n_faces() > 0 && b.n_faces() > 0)
    throw InvalidMesh(fmt::format("surface union: no face of either surface lies outside the other ({} + {} faces "
                                  "inside): they are the same body twice",
                                  result.removed_faces_a, result.removed_faces_b));
  try {
    result.mesh = compact(split.points, faces);
  } catch (const InvalidMesh& e) {
    throw InvalidMesh(fmt::format("surface union: the surfaces split along their crossing curves, less their parts "
                                  "inside each other, did not give a manifold surface ({})",
                                  e.what()));
  }
  logger().debug("surface union: split along {} crossing curve(s), removed {} + {} faces inside the other",
                 result.joined_loops, result.removed_faces_a, result.removed_faces_b);
  return result;
}

//! A surface united with itself is itself; the general path would find every face both inside
//! and on the other surface and remove them all.
UnionResult itself(const Mesh& a)
{
  UnionResult result;
  result.mesh = a;
  result.mesh.garbage_collection();
  return result;
}

} // namespace

UnionResult surface_union(const Mesh& a, const Mesh& b)
{
  if (same_triangles(a, b))
    return itself(a);
  if (self_intersections(a).empty() && self_intersections(b).empty())
    return exact_union(a, b);
  const Overlap o = overlap_of(a, b);
  return zipped_joint(a, b, faces_to_remove(o.a, false, false), faces_to_remove(o.b, false, false));
}

UnionResult merge_touching_surfaces(const Mesh& a, const Mesh& b)
{
  if (same_triangles(a, b))
    return itself(a);
  const Overlap o = overlap_of(a, b);
  // Each surface's inside must be the side away from the other, the region that joins.
  const bool reverse_a = mostly_inside(b, o.b);
  const bool reverse_b = mostly_inside(a, o.a);
  // Where surfaces that just touched close in on each other the two sides of the joint would meet
  // at a cusp, whose faces the next steps push through each other: the faces within an edge of
  // the other surface go too, so that the joint starts about an edge wide. Only at a fresh contact,
  // where no face lies deeper inside the other than that, and only if something is left to join:
  // bodies that overlap deeply, or whose surfaces run within an edge of each other all over, get
  // their plain union, as surface_union forms it (the widening removed every face of two spheres
  // 0.2 apart: "no face of either lies outside the other", issue 33).
  // A surface that crosses itself (the flow's own crossing, met by another body in the same step)
  // has no inside to split by: it is zipped as before.
  const bool exact = self_intersections(a).empty() && self_intersections(b).empty();
  const auto merged = [&](bool widen) {
    const Mesh first = reverse_a ? reversed(a) : a, second = reverse_b ? reversed(b) : b;
    if (!widen && exact)
      return exact_union(first, second);
    return zipped_joint(first, second, faces_to_remove(o.a, reverse_b, widen), faces_to_remove(o.b, reverse_a, widen));
  };
  // A band zipped across loops that do not face each other crosses itself, or the surface: then
  // the exact union (on CGAL's bones.off, 29 face pairs of the bands crossed).
  UnionResult result;
  const bool fresh = fresh_contact(o.a, reverse_b) && fresh_contact(o.b, reverse_a);
  try {
    result = merged(fresh);
    if (fresh && exact && !self_intersections(result.mesh).empty())
      result = merged(false);
  } catch (const InvalidMesh&) {
    if (!fresh)
      throw;
    result = merged(false);
  }
  if (reverse_a)
    result.mesh = reversed(result.mesh);
  return result;
}

} // namespace sdflow
