//! compare_meshes EXPECTED ACTUAL: succeeds (exit 0) when two mesh files hold the same triangles
//! over the same number of vertices, with coordinates equal to single precision: |Δ| ≤ ε_float ·
//! max |coordinate|, twice the error of rounding a double to the nearest float. Used to check the
//! plugin's output (MeshLab stores floats) against `sdflow run` (doubles). Exit 1 on a mismatch,
//! 2 on an unreadable file.

#include "sdflow/errors.h"
#include "sdflow/io/io.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>

int main(int argc, char** argv)
{
  if (argc != 3) {
    std::cerr << "usage: compare_meshes EXPECTED ACTUAL\n";
    return 2;
  }
  try {
    const sdflow::PolygonSoup expected = sdflow::read_polygon_soup(argv[1]);
    const sdflow::PolygonSoup actual = sdflow::read_polygon_soup(argv[2]);
    if (expected.points.size() != actual.points.size() || expected.polygons.size() != actual.polygons.size()) {
      std::cerr << "compare_meshes: " << expected.points.size() << " vertices and " << expected.polygons.size()
                << " faces expected, got " << actual.points.size() << " and " << actual.polygons.size() << '\n';
      return 1;
    }
    for (std::size_t f = 0; f < expected.polygons.size(); ++f)
      if (expected.polygons[f] != actual.polygons[f]) {
        std::cerr << "compare_meshes: face " << f << " differs\n";
        return 1;
      }
    double scale = 0, largest_difference = 0;
    std::size_t worst = 0;
    for (std::size_t v = 0; v < expected.points.size(); ++v) {
      scale = std::max(scale, expected.points[v].cwiseAbs().maxCoeff());
      const double difference = (expected.points[v] - actual.points[v]).cwiseAbs().maxCoeff();
      if (!std::isfinite(difference)) {
        std::cerr << "compare_meshes: vertex " << v << " is not finite\n";
        return 1;
      }
      if (difference > largest_difference) {
        largest_difference = difference;
        worst = v;
      }
    }
    const double tolerance = std::numeric_limits<float>::epsilon() * scale;
    std::cout << "compare_meshes: " << expected.points.size() << " vertices, " << expected.polygons.size()
              << " faces; largest coordinate difference " << largest_difference << " at vertex " << worst
              << " (tolerance " << tolerance << ")\n";
    return largest_difference <= tolerance ? 0 : 1;
  } catch (const sdflow::Error& e) {
    std::cerr << "compare_meshes: " << e.what() << '\n';
    return 2;
  }
}
