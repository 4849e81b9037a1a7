#include "support/exact_reference.h"

#include <gmpxx.h>

#include <algorithm>
#include <optional>
#include <utility>

namespace sdflow::reference {
namespace {

using Q = mpq_class;
using Q3 = std::array<Q, 3>;

Q3 exact(const Eigen::Vector3d& p) { return {Q(p.x()), Q(p.y()), Q(p.z())}; }
Q3 sub(const Q3& a, const Q3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Q3 add(const Q3& a, const Q3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Q3 scale(const Q& s, const Q3& a) { return {s * a[0], s * a[1], s * a[2]}; }
Q dot(const Q3& a, const Q3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Q3 cross(const Q3& a, const Q3& b)
{
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
bool is_zero(const Q3& a) { return sgn(a[0]) == 0 && sgn(a[1]) == 0 && sgn(a[2]) == 0; }

//! Parameter interval [t0, t1] of the points P + t (Q - P), 0 ≤ t ≤ 1, inside closed triangle abc.
std::optional<std::pair<Q, Q>> edge_in_triangle(const Q3& p, const Q3& q, const std::array<Q3, 3>& tri)
{
  const Q3 n = cross(sub(tri[1], tri[0]), sub(tri[2], tri[0]));
  const Q fp = dot(n, sub(p, tri[0])), fq = dot(n, sub(q, tri[0]));
  // g_e(W) ≥ 0 is the inner half-plane (within the triangle's plane) of edge e.
  auto inner = [&](int e, const Q3& w) {
    return dot(cross(sub(tri[(e + 1) % 3], tri[e]), sub(w, tri[e])), n);
  };
  if (sgn(fp) == 0 && sgn(fq) == 0) {
    Q t0 = 0, t1 = 1;
    for (int e = 0; e < 3; ++e) {
      const Q gp = inner(e, p), gq = inner(e, q);
      if (gp == gq) {
        if (sgn(gp) < 0)
          return std::nullopt;
        continue;
      }
      const Q bound = gp / (gp - gq);
      if (gq > gp)
        t0 = std::max(t0, bound);
      else
        t1 = std::min(t1, bound);
    }
    if (t0 > t1)
      return std::nullopt;
    return std::make_pair(t0, t1);
  }
  if (sgn(fp) * sgn(fq) > 0 || fp == fq)
    return std::nullopt;
  const Q t = fp / (fp - fq);
  const Q3 w = add(p, scale(t, sub(q, p)));
  for (int e = 0; e < 3; ++e)
    if (sgn(inner(e, w)) < 0)
      return std::nullopt;
  return std::make_pair(t, t);
}

} // namespace

bool degenerate(const std::array<Eigen::Vector3d, 3>& t)
{
  const Q3 a = exact(t[0]), b = exact(t[1]), c = exact(t[2]);
  return is_zero(cross(sub(b, a), sub(c, a)));
}

bool faces_intersect(const std::array<Eigen::Vector3d, 3>& t, const std::array<int, 3>& ti,
                     const std::array<Eigen::Vector3d, 3>& u, const std::array<int, 3>& ui)
{
  std::vector<Q3> shared;
  for (int i = 0; i < 3; ++i)
    if (std::find(ui.begin(), ui.end(), ti[i]) != ui.end())
      shared.push_back(exact(t[i]));
  if (shared.size() == 3)
    return true;
  auto in_shared = [&](const Q3& w) {
    if (shared.empty())
      return false;
    if (shared.size() == 1)
      return is_zero(sub(w, shared[0]));
    const Q3 d = sub(shared[1], shared[0]), r = sub(w, shared[0]);
    if (!is_zero(cross(r, d)))
      return false;
    const Q s = dot(r, d);
    return sgn(s) >= 0 && s <= dot(d, d);
  };
  const std::array<Q3, 3> T = {exact(t[0]), exact(t[1]), exact(t[2])};
  const std::array<Q3, 3> U = {exact(u[0]), exact(u[1]), exact(u[2])};
  for (int pass = 0; pass < 2; ++pass) {
    const auto& from = pass == 0 ? T : U;
    const auto& into = pass == 0 ? U : T;
    for (int e = 0; e < 3; ++e) {
      const Q3& p = from[e];
      const Q3& q = from[(e + 1) % 3];
      const auto interval = edge_in_triangle(p, q, into);
      if (!interval)
        continue;
      for (const Q& s : {interval->first, interval->second})
        if (!in_shared(add(p, scale(s, sub(q, p)))))
          return true;
    }
  }
  return false;
}

namespace {

std::array<Eigen::Vector3d, 3> corners(const Mesh& mesh, Mesh::FaceHandle f, std::array<int, 3>& ids)
{
  std::array<Eigen::Vector3d, 3> c;
  int k = 0;
  for (auto v : mesh.fv_range(f)) {
    ids[k] = v.idx();
    c[k++] = to_eigen(mesh.point(v));
  }
  return c;
}

bool boxes_overlap(const std::array<Eigen::Vector3d, 3>& t, const std::array<Eigen::Vector3d, 3>& u)
{
  for (int k = 0; k < 3; ++k) {
    const double tlo = std::min({t[0][k], t[1][k], t[2][k]}), thi = std::max({t[0][k], t[1][k], t[2][k]});
    const double ulo = std::min({u[0][k], u[1][k], u[2][k]}), uhi = std::max({u[0][k], u[1][k], u[2][k]});
    if (thi < ulo || uhi < tlo)
      return false;
  }
  return true;
}

} // namespace

std::vector<FacePair> self_intersections(const Mesh& mesh)
{
  const int n = static_cast<int>(mesh.n_faces());
  std::vector<std::array<Eigen::Vector3d, 3>> c(n);
  std::vector<std::array<int, 3>> id(n);
  std::vector<char> flat(n);
  for (auto f : mesh.faces()) {
    c[f.idx()] = corners(mesh, f, id[f.idx()]);
    flat[f.idx()] = degenerate(c[f.idx()]);
  }
  std::vector<FacePair> pairs;
  for (int f = 0; f < n; ++f) {
    if (flat[f]) {
      pairs.push_back({f, f});
      continue;
    }
    for (int g = f + 1; g < n; ++g)
      if (!flat[g] && boxes_overlap(c[f], c[g]) && faces_intersect(c[f], id[f], c[g], id[g]))
        pairs.push_back({f, g});
  }
  return pairs;
}

std::vector<FacePair> surface_intersections(const Mesh& a, const Mesh& b)
{
  std::vector<FacePair> pairs;
  std::array<int, 3> ia, ib;
  for (auto f : a.faces()) {
    const auto ca = corners(a, f, ia);
    for (int k = 0; k < 3; ++k)
      ia[k] = -1 - ia[k]; // no vertex of a is a vertex of b
    for (auto g : b.faces()) {
      const auto cb = corners(b, g, ib);
      if (boxes_overlap(ca, cb) && faces_intersect(ca, ia, cb, ib))
        pairs.push_back({f.idx(), g.idx()});
    }
  }
  return pairs;
}

} // namespace sdflow::reference
