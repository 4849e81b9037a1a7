#pragma once
//! \file topology.h
//! \brief Connected components and their topology (Euler characteristic, genus, boundary loops).

#include "sdflow/mesh.h"

#include <vector>

namespace sdflow {

//! Topology of one connected component (connected through edges).
struct ComponentTopology {
  int vertices = 0;
  int edges = 0;
  int faces = 0;
  int boundary_loops = 0;
  int euler_characteristic = 0; //!< V - E + F
  int genus = 0;                //!< (2 - χ - b) / 2
  bool closed() const { return boundary_loops == 0; }
};

//! A surface's topology in total: what two triangulations of one surface share.
struct TopologyCount {
  int components = 0;
  int genus = 0; //!< summed over the components
  int boundary_loops = 0;
  bool operator==(const TopologyCount&) const = default;
};

//! Component id of every face (0-based, numbered in order of each component's first face).
std::vector<int> face_component_ids(const Mesh& mesh, int* component_count = nullptr);

//! Topology of each component, in the order of face_component_ids.
std::vector<ComponentTopology> component_topology(const Mesh& mesh);

//! The components, total genus and boundary loops of `mesh` (component_topology summed).
TopologyCount count_topology(const Mesh& mesh);

//! The boundary loops of `mesh`, each as its boundary halfedges h, next(h), … in order, the loops
//! in the order of their first halfedge's index.
std::vector<std::vector<Mesh::HalfedgeHandle>> boundary_loops(const Mesh& mesh);

//! The length of each boundary loop, in the order of boundary_loops.
std::vector<double> boundary_loop_lengths(const Mesh& mesh);

} // namespace sdflow
