#include "sdflow/geometry/cotangent_cache.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/detail/mixed_voronoi.h"

#include <fmt/format.h>

#include <algorithm>

namespace sdflow {
namespace {

std::array<int, 3> corners(const Mesh& mesh, Mesh::FaceHandle f)
{
  std::array<int, 3> idx{};
  int k = 0;
  for (auto v : mesh.fv_range(f))
    idx[k++] = v.idx();
  return idx;
}

} // namespace

CotangentCache::CotangentCache(const Mesh& mesh)
{
  triangles_.reserve(mesh.n_faces());
  for (auto f : mesh.faces()) {
    if (mesh.valence(f) != 3)
      throw InvalidMesh(fmt::format("CotangentCache: face {} is not a triangle", f.idx()));
    triangles_.push_back(corners(mesh, f));
  }
  build_pattern(static_cast<Eigen::Index>(mesh.n_vertices()));
}

CotangentCache::CotangentCache(Eigen::Index vertices, const FaceIndices& triangles)
{
  triangles_.resize(static_cast<std::size_t>(triangles.rows()));
  for (Eigen::Index f = 0; f < triangles.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int v = triangles(f, c);
      if (v < 0 || v >= vertices)
        throw InvalidMesh(fmt::format("CotangentCache: triangle {} has corner {} outside the {} vertices", f, v,
                                      vertices));
      triangles_[static_cast<std::size_t>(f)][c] = v;
    }
  build_pattern(vertices);
}

void CotangentCache::build_pattern(Eigen::Index n)
{
  // L's pattern, column by column: a vertex and every vertex it shares a triangle with, ascending
  // (what setFromTriplets makes of the corner pairs, at a fraction of its cost: it sorts 12 triplets
  // a triangle twice over).
  std::vector<int> start(static_cast<std::size_t>(n) + 1, 0);
  for (const auto& t : triangles_)
    for (const int v : t)
      start[static_cast<std::size_t>(v) + 1] += 3;
  for (std::size_t v = 0; v < static_cast<std::size_t>(n); ++v)
    start[v + 1] += start[v];
  std::vector<int> listed(static_cast<std::size_t>(start.back()));
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (const auto& t : triangles_)
    for (const int v : t)
      for (const int w : t)
        listed[static_cast<std::size_t>(fill[static_cast<std::size_t>(v)]++)] = w;
  std::vector<int> outer(static_cast<std::size_t>(n) + 1, 0), inner;
  inner.reserve(listed.size() / 2 + static_cast<std::size_t>(n));
  for (std::size_t v = 0; v < static_cast<std::size_t>(n); ++v) {
    const auto first = listed.begin() + start[v], last = listed.begin() + start[v + 1];
    std::sort(first, last);
    inner.insert(inner.end(), first, std::unique(first, last));
    outer[v + 1] = static_cast<int>(inner.size());
  }
  pattern_.resize(n, n);
  pattern_.resizeNonZeros(static_cast<Eigen::Index>(inner.size()));
  std::copy(outer.begin(), outer.end(), pattern_.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), pattern_.innerIndexPtr());
  std::fill(pattern_.valuePtr(), pattern_.valuePtr() + inner.size(), 0.0);
  const auto slot = [&](int row, int col) {
    const int* begin = pattern_.innerIndexPtr() + pattern_.outerIndexPtr()[col];
    const int* end = pattern_.innerIndexPtr() + pattern_.outerIndexPtr()[col + 1];
    return static_cast<int>(std::lower_bound(begin, end, row) - pattern_.innerIndexPtr());
  };
  slots_.reserve(triangles_.size());
  for (const auto& t : triangles_) {
    std::array<int, 12> s{};
    for (int c = 0; c < 3; ++c) {
      const int j = t[(c + 1) % 3], k = t[(c + 2) % 3];
      s[4 * c] = slot(j, k);
      s[4 * c + 1] = slot(k, j);
      s[4 * c + 2] = slot(j, j);
      s[4 * c + 3] = slot(k, k);
    }
    slots_.push_back(s);
  }
}

bool CotangentCache::fits(const Mesh& mesh) const
{
  if (mesh.n_faces() != triangles_.size() || static_cast<Eigen::Index>(mesh.n_vertices()) != pattern_.rows())
    return false;
  for (auto f : mesh.faces())
    if (corners(mesh, f) != triangles_[f.idx()])
      return false;
  return true;
}

void CotangentCache::assemble(const Mesh& mesh, SparseMatrix& laplacian, Eigen::VectorXd& areas) const
{
  if (!fits(mesh))
    throw InvalidParameter("CotangentCache: the mesh's connectivity is not the one the cache was built for");
  laplacian = pattern_;
  double* values = laplacian.valuePtr();
  std::fill(values, values + laplacian.nonZeros(), 0.0);
  areas = Eigen::VectorXd::Zero(mesh.n_vertices());
  for (std::size_t f = 0; f < triangles_.size(); ++f) {
    const auto& t = triangles_[f];
    const std::array<Eigen::Vector3d, 3> p{to_eigen(mesh.point(Mesh::VertexHandle(t[0]))),
                                           to_eigen(mesh.point(Mesh::VertexHandle(t[1]))),
                                           to_eigen(mesh.point(Mesh::VertexHandle(t[2])))};
    const double twice_area = (p[1] - p[0]).cross(p[2] - p[0]).norm();
    if (!(twice_area > 0))
      throw InvalidMesh(fmt::format("cotangent_laplacian: triangle {} has zero area", f));
    std::array<double, 3> dots{};
    for (int c = 0; c < 3; ++c) {
      dots[c] = (p[(c + 1) % 3] - p[c]).dot(p[(c + 2) % 3] - p[c]);
      const double half_cot = 0.5 * dots[c] / twice_area;
      const auto& s = slots_[f];
      values[s[4 * c]] += half_cot;
      values[s[4 * c + 1]] += half_cot;
      values[s[4 * c + 2]] += -half_cot;
      values[s[4 * c + 3]] += -half_cot;
    }
    detail::add_mixed_voronoi_areas(p, t, dots, twice_area, areas);
  }
}

} // namespace sdflow
