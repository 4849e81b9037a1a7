#pragma once
//! \file meshed_shapes.h
//! \brief The paper's shapes meshed once per test run at small, fast resolutions.

#include "sdflow/shapes/catalogue.h"
#include "sdflow/shapes/mesher.h"

#include <map>
#include <string>
#include <vector>

namespace sdflow::testing {

//! One catalogue shape, how to mesh it, and the topology the paper gives it.
struct ShapeCase {
  std::string name;
  std::map<std::string, double> parameters;
  double edge_length;
  int genus;
  int boundary_loops;
  bool smooth; //!< no blended creases: held to the 30° quality target
};

//! Every catalogue shape (the three-spheres disk shrunk to radius 9 so the test mesh stays small;
//! the topology does not depend on it).
inline const std::vector<ShapeCase>& shape_cases()
{
  static const std::vector<ShapeCase> cases = {
      {"sphere", {}, 0.15, 0, 0, true},
      {"ellipsoid", {}, 0.6, 0, 0, true},
      {"torus", {}, 0.6, 1, 0, true},
      {"dumbbell", {}, 0.8, 0, 0, true},
      {"sintering", {}, 0.45, 5, 0, false},
      {"spheres-on-plane", {{"disk-radius", 9}}, 0.45, 3, 1, false},
  };
  return cases;
}

//! The shape and its mesh, computed on first use.
struct MeshedShape {
  ImplicitSurface surface;
  MesherResult result;
};

inline const MeshedShape& meshed(const ShapeCase& c)
{
  static std::map<std::string, MeshedShape> cache;
  auto it = cache.find(c.name);
  if (it == cache.end()) {
    ImplicitSurface surface = make_shape(c.name, c.parameters);
    MesherResult result = mesh_implicit_surface(surface, {.edge_length = c.edge_length});
    it = cache.emplace(c.name, MeshedShape{std::move(surface), std::move(result)}).first;
  }
  return it->second;
}

} // namespace sdflow::testing
