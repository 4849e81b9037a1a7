//! The C++ side of python/tests/test_operators.py: the toolbox's operators on a mesh file, printed
//! as hexadecimal floats (exact), one quantity a line: `name count v0 v1 ...`.
//!   sdflow_operators_reference MESH

#include "sdflow/flow/scheme.h"
#include "sdflow/geometry/curvature.h"
#include "sdflow/geometry/laplacian.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/normals.h"
#include "sdflow/io/io.h"

#include <cstdio>
#include <exception>

namespace {

void print(const char* name, const double* values, long count)
{
  std::printf("%s %ld", name, count);
  for (long i = 0; i < count; ++i)
    std::printf(" %a", values[i]);
  std::printf("\n");
}

} // namespace

int main(int argc, char** argv)
{
  if (argc != 2) {
    std::fprintf(stderr, "usage: sdflow_operators_reference MESH\n");
    return 2;
  }
  try {
    using namespace sdflow;
    const Mesh mesh = read_mesh(argv[1]).mesh;
    const VertexVectors n = vertex_normals(mesh);
    print("normals", n.data(), n.size());
    for (const auto& [name, curvature] :
         {std::pair{"H_cotangent", CurvatureOptions{.method = CurvatureMethod::cotangent}},
          std::pair{"H_normal_integral", CurvatureOptions{}},
          std::pair{"H_normal_integral_angle_sum", CurvatureOptions{.normalisation = AngleNormalisation::angle_sum}}}) {
      SchemeOptions options;
      options.curvature = curvature;
      const Eigen::VectorXd h = flow_operators(mesh, options).curvature;
      print(name, h.data(), h.size());
    }
    SchemeOptions volume_gradient;
    volume_gradient.mass = VertexMass::volume_gradient;
    const Eigen::VectorXd hv = flow_operators(mesh, volume_gradient).curvature;
    print("H_cotangent_volume_gradient", hv.data(), hv.size());
    const Eigen::VectorXd h9 = mean_curvature(mesh, n);
    print("H_eq9_free_function", h9.data(), h9.size());
    const Eigen::VectorXd a = mixed_voronoi_areas(mesh);
    print("areas_voronoi", a.data(), a.size());
    const Eigen::VectorXd g = volume_gradient_areas(mesh, n);
    print("areas_volume_gradient", g.data(), g.size());
    SparseMatrix l = cotangent_laplacian(mesh);
    l.makeCompressed();
    print("laplacian_values", l.valuePtr(), l.nonZeros());
    const CurvatureDeviation d = curvature_deviation(h9, a);
    const double scalars[] = {surface_area(mesh), enclosed_volume(mesh), d.mean, d.deviation, mean_edge_length(mesh)};
    print("area_volume_mean_deviation_edge", scalars, 5);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
