#pragma once
//! \file surgery_patch.h
//! \brief The patch a local surgery cuts out and rebuilds (local_surgery.h): the faces near the
//! self-intersecting ones, grown until the surface kept around it is a manifold whose cut is a
//! set of simple loops without sharp teeth.

#include "sdflow/mesh.h"
#include "sdflow/spatial/intersect.h"

#include <vector>

namespace sdflow {

//! Faces of a mesh split into the patch and the kept surface.
struct SurgeryPatch {
  std::vector<char> in_patch;    //!< by face index: 1 for the faces of the patch
  int faces = 0;                 //!< faces in the patch
  bool touches_boundary = false; //!< a patch face has a vertex on a true boundary of the mesh
};

//! The faces with a vertex within `radius` (Euclidean) of a vertex of a face in `crossings`, the
//! crossing faces themselves included; then, until nothing changes, every face of a vertex around
//! which the kept faces form more than one fan (so that the cut is a set of simple loops and the
//! patch a manifold), every face of a cut vertex where the kept faces span less than 2π/3 (a
//! tooth of kept faces, sharper than a straight cut across an equilateral mesh ever turns: the
//! rebuild could not pass beside it) and every kept component of fewer than `min_kept_faces`
//! faces (islands left between crossing sites). The mesh must carry no deleted elements.
SurgeryPatch surgery_patch(const Mesh& mesh, const std::vector<FacePair>& crossings, double radius,
                           int min_kept_faces);

//! The patch `in_patch` (by face index) grown as surgery_patch grows its first faces: until the
//! kept surface is a manifold with a cut of simple loops, without sharp teeth or small islands.
SurgeryPatch completed_patch(const Mesh& mesh, std::vector<char> in_patch, int min_kept_faces);

//! Moves into the patch (`in_patch`, by face index) every face of a vertex around which the faces
//! kept form more than one fan, until there is none; returns whether any face moved.
bool separate_split_fans(const Mesh& mesh, std::vector<char>& in_patch);

} // namespace sdflow
