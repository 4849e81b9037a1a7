#include "sdflow/check/tetgen_volume.h"

#include "sdflow/check/span.h"
#include "sdflow/errors.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/topology.h"

#include <fmt/format.h>
#include <tetgen.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace sdflow {
namespace {

//! A closed component is flat when |volume| ≤ this × area^(3/2) (as validation decides).
constexpr double flat_volume_tolerance = 1e-10;

//! TetGen's documented exit codes (tetgen.h, terminatetetgen).
std::string tetgen_failure(int code)
{
  switch (code) {
  case 1: return "out of memory";
  case 2: return "internal error";
  case 3: return "the surface intersects itself";
  case 4: return "a feature is too small for TetGen's tolerance";
  case 5: return "two facets are too close to each other";
  case 10: return "invalid input";
  default: return fmt::format("TetGen error code {}", code);
  }
}

//! Refuse what TetGen 1.5.0 cannot take without aborting the process (an assertion in its
//! predicates on a flat body) or crashing (a component whose extent dwarfs its edges, like one
//! vertex far away): a reason instead of a dead process.
void screen_for_tetgen(const std::vector<double>& points, const std::vector<int>& triangles, double volume,
                       int component)
{
  const auto point = [&](int i) { return Eigen::Vector3d(points[3 * i], points[3 * i + 1], points[3 * i + 2]); };
  Eigen::AlignedBox3d box;
  double area = 0, shortest = std::numeric_limits<double>::infinity();
  for (std::size_t t = 0; t + 2 < triangles.size(); t += 3) {
    const Eigen::Vector3d a = point(triangles[t]), b = point(triangles[t + 1]), c = point(triangles[t + 2]);
    area += 0.5 * (b - a).cross(c - a).norm();
    shortest = std::min({shortest, (b - a).norm(), (c - b).norm(), (a - c).norm()});
    box.extend(a);
  }
  if (std::abs(volume) <= flat_volume_tolerance * std::pow(area, 1.5))
    throw InvalidMesh(fmt::format("TetGen volume check: component {} encloses no volume (area {:.6g}, volume {:.3g}): "
                                  "a flat, degenerate body that TetGen cannot tetrahedralise", component, area, volume));
  const double extent = box.diagonal().norm();
  if (!(extent <= max_span_ratio * shortest))
    throw InvalidMesh(fmt::format("TetGen volume check: component {} spans {:.3g} with edges as short as {:.3g} "
                                  "(ratio {:.2g}, above {:g}): beyond what TetGen's tolerances can tetrahedralise "
                                  "reliably; a vertex far from the others? (skip the cross-check with --no-tetgen)",
                                  component, extent, shortest, extent / shortest, max_span_ratio));
}

double tet_volume(const double* a, const double* b, const double* c, const double* d)
{
  const Eigen::Vector3d ab(b[0] - a[0], b[1] - a[1], b[2] - a[2]);
  const Eigen::Vector3d ac(c[0] - a[0], c[1] - a[1], c[2] - a[2]);
  const Eigen::Vector3d ad(d[0] - a[0], d[1] - a[1], d[2] - a[2]);
  return std::abs(ab.dot(ac.cross(ad))) / 6.0;
}

ComponentVolumeCheck check_component(const Mesh& mesh, const std::vector<int>& face_id, int component)
{
  ComponentVolumeCheck result;
  result.component = component;
  std::vector<int> local(mesh.n_vertices(), -1);
  std::vector<double> points;
  std::vector<int> triangles;
  for (auto f : mesh.faces()) {
    if (face_id[f.idx()] != component)
      continue;
    result.divergence_volume += cone_volume(mesh, f);
    for (auto v : f.vertices()) {
      if (local[v.idx()] < 0) {
        local[v.idx()] = static_cast<int>(points.size() / 3);
        const auto& p = mesh.point(v);
        points.insert(points.end(), {p[0], p[1], p[2]});
      }
      triangles.push_back(local[v.idx()]);
    }
  }

  screen_for_tetgen(points, triangles, result.divergence_volume, component);

  tetgenio in, out;
  in.firstnumber = 0;
  in.numberofpoints = static_cast<int>(points.size() / 3);
  in.pointlist = new REAL[points.size()];
  std::copy(points.begin(), points.end(), in.pointlist);
  in.numberoffacets = static_cast<int>(triangles.size() / 3);
  in.facetlist = new tetgenio::facet[in.numberoffacets];
  in.facetmarkerlist = nullptr;
  for (int i = 0; i < in.numberoffacets; ++i) {
    tetgenio::facet& facet = in.facetlist[i];
    tetgenio::init(&facet);
    facet.numberofpolygons = 1;
    facet.polygonlist = new tetgenio::polygon[1];
    tetgenio::init(&facet.polygonlist[0]);
    facet.polygonlist[0].numberofvertices = 3;
    facet.polygonlist[0].vertexlist = new int[3]{triangles[3 * i], triangles[3 * i + 1], triangles[3 * i + 2]};
  }

  // Debian's TetGen 1.5.0 frees its memory pools twice when it aborts a tetrahedralisation (a
  // crash, not an exception), so self-intersections are screened first with its detection mode
  // (d), which reports intersecting facets instead of aborting.
  {
    tetgenio screened;
    char detect[] = "pdQz";
    try {
      tetrahedralize(detect, &in, &screened);
    } catch (int code) {
      throw InvalidMesh(fmt::format("TetGen could not check component {}: {}", component, tetgen_failure(code)));
    }
    if (screened.numberoftrifaces > 0)
      throw InvalidMesh(fmt::format("TetGen could not tetrahedralise component {}: {} ({} facets intersect)", component,
                                    tetgen_failure(3), screened.numberoftrifaces));
  }
  // p: the input is a piecewise linear complex; Y: keep the surface as given (no boundary Steiner
  // points); Q: quiet; z: zero-based indices.
  char switches[] = "pYQz";
  try {
    tetrahedralize(switches, &in, &out);
  } catch (int code) {
    throw InvalidMesh(fmt::format("TetGen could not tetrahedralise component {}: {}", component, tetgen_failure(code)));
  }

  result.tetrahedra = out.numberoftetrahedra;
  for (int t = 0; t < out.numberoftetrahedra; ++t) {
    const int* corner = out.tetrahedronlist + t * out.numberofcorners;
    result.tetgen_volume += tet_volume(out.pointlist + 3 * corner[0], out.pointlist + 3 * corner[1],
                                       out.pointlist + 3 * corner[2], out.pointlist + 3 * corner[3]);
  }
  // TetGen's volume is unsigned; a cavity (outward = into the void) counts negative in the
  // divergence theorem, so it does here too: like is compared with like.
  if (result.divergence_volume < 0)
    result.tetgen_volume = -result.tetgen_volume;
  return result;
}

} // namespace

double ComponentVolumeCheck::relative_difference() const
{
  return std::abs(tetgen_volume - divergence_volume) / std::max(std::abs(divergence_volume), 1e-300);
}

std::vector<ComponentVolumeCheck> tetgen_volume_check(const Mesh& mesh)
{
  int count = 0;
  face_component_ids(mesh, &count);
  std::vector<int> all(static_cast<std::size_t>(count));
  for (int c = 0; c < count; ++c)
    all[c] = c;
  return tetgen_volume_check(mesh, all);
}

std::vector<ComponentVolumeCheck> tetgen_volume_check(const Mesh& mesh, const std::vector<int>& components)
{
  int count = 0;
  const std::vector<int> face_id = face_component_ids(mesh, &count);
  const std::vector<ComponentTopology> topology = component_topology(mesh);
  std::vector<ComponentVolumeCheck> checks;
  for (int c : components)
    if (c >= 0 && c < count && topology[c].closed())
      checks.push_back(check_component(mesh, face_id, c));
  return checks;
}

} // namespace sdflow
