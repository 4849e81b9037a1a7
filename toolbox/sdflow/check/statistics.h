#pragma once
//! \file statistics.h
//! \brief Everything `sdflow stats` reports about a surface, computed in one place.

#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/quality.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/mesh.h"

#include <optional>
#include <string>
#include <vector>

namespace sdflow {

struct ComponentStatistics {
  ComponentTopology topology;
  double area = 0;
  double volume = 0;                   //!< divergence theorem; 0 for components with boundary
  //! The volume a run measures (material_volume.h): each boundary loop closed by a flat cap; the
  //! divergence-theorem volume on a closed component.
  double material_volume = 0;
  std::optional<double> tetgen_volume; //!< TetGen's tetrahedral volume, closed components only
  int tetrahedra = 0;
  //! Faces of this component in an intersecting pair: TetGen is not called on it (it refuses a
  //! surface that crosses itself), and its volume is not that of a solid.
  long crossing_faces = 0;
};

struct MeshStatistics {
  int vertices = 0, edges = 0, faces = 0;
  std::vector<ComponentStatistics> components;
  int genus = 0;          //!< summed over components
  int boundary_loops = 0; //!< summed over components
  double area = 0;
  double volume = 0;                   //!< summed over closed components
  double material_volume = 0;          //!< summed over all components (ComponentStatistics)
  //! Summed over closed components, when every one was checked (none crosses a face).
  std::optional<double> tetgen_volume;
  //! Why TetGen was not called on some closed components (empty when it was on all or not asked).
  std::string tetgen_skipped;
  CurvatureDeviation curvature;        //!< H̃ and H_dev with eq. (9) and mixed Voronoi areas
  //! Pairs of triangles that intersect (not counting neighbours meeting at their shared vertex or
  //! edge): components crossing each other or one crossing itself. Where there are any, the
  //! volumes are not those of a solid and the body/cavity orientation is not meaningful.
  long self_intersecting_pairs = 0;
  MeshQuality quality;
};

struct StatisticsOptions {
  //! Cross-check each closed component's volume with TetGen (costs a tetrahedralisation); with
  //! the intersection check on, components with a face in an intersecting pair are left out
  //! (MeshStatistics::tetgen_skipped says so): TetGen refuses a crossing surface.
  bool tetgen_check = true;
  //! Count the intersecting triangle pairs (spatial/intersect.h).
  bool intersection_check = true;
};

//! Topology, area, volume (both methods), mean curvature deviation and quality of `mesh`.
MeshStatistics mesh_statistics(const Mesh& mesh, const StatisticsOptions& options = {});

} // namespace sdflow
