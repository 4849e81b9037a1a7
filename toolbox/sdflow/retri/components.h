#pragma once
//! \file components.h
//! \brief Connected components (through edges, as face_component_ids in geometry/topology.h):
//! split a surface into one mesh per component, or keep the large ones (paper §3.2.1 and
//! Appendix A: after a pinch-off each piece evolves on its own, and small debris is dropped).

#include "sdflow/mesh.h"

#include <vector>

namespace sdflow {

//! Which components to keep: first those with at least `min_faces` triangles (and, when closed,
//! enclosing a volume of at least `min_thickness` times their area), then of those the
//! `keep_largest` largest (ties go to the component met first in face order).
struct ComponentOptions {
  int min_faces = 1;    //!< ≥ 1; the default keeps every component
  int keep_largest = 0; //!< ≥ 0; 0 keeps all that pass min_faces
  //! ≥ 0; a closed component with |volume| < min_thickness · area is a collapsed double sheet
  //! (debris of a surgery). 0 keeps them all.
  double min_thickness = 0;
};

//! The kept components as one mesh, and the bookkeeping.
struct ComponentSelection {
  Mesh mesh;                  //!< the kept components (garbage-collected, no isolated vertex)
  std::vector<int> faces;     //!< triangle count of every input component, by component id
  std::vector<int> kept;      //!< ids of the kept components, largest first
  std::vector<int> dropped;   //!< ids of the others, largest first
};

//! Keep the components selected by `options`, in one mesh. Throws InvalidParameter for options
//! out of range.
ComponentSelection keep_components(const Mesh& mesh, const ComponentOptions& options = {});

//! The components selected by `options`, each as its own mesh, largest first. Vertices and faces
//! keep their relative input order.
std::vector<Mesh> split_components(const Mesh& mesh, const ComponentOptions& options = {});

} // namespace sdflow
