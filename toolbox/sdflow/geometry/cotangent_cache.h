#pragma once
//! \file cotangent_cache.h
//! \brief The operators of eq. (10), L and M, for one fixed connectivity: the sparsity pattern and
//! each triangle's slots in it are found once, so a step only recomputes the values (the pattern
//! build dominates `cotangent_laplacian`). Values are those of `cotangent_laplacian` and
//! `mixed_voronoi_areas` (Meyer, Desbrun, Schröder, Barr 2003), summed in the same order.

#include "sdflow/geometry/laplacian.h"
#include "sdflow/mesh.h"

#include <array>
#include <vector>

namespace sdflow {

class CotangentCache {
public:
  //! Record the connectivity of `mesh` and the slots of its triangles in L's pattern.
  explicit CotangentCache(const Mesh& mesh);

  //! The same for the mesh of `vertices` vertices whose faces' corners, in face order and as the
  //! face's vertex circulator lists them, are the rows of `triangles` (make_mesh keeps them so):
  //! it can be built beside the mesh itself.
  CotangentCache(Eigen::Index vertices, const FaceIndices& triangles);

  //! True if `mesh` has the connectivity this cache was built for (same triangles, same order).
  bool fits(const Mesh& mesh) const;

  //! L (symmetric cotangent matrix) and the mixed Voronoi areas of `mesh`'s current positions.
  //! Throws InvalidParameter if the mesh does not fit, InvalidMesh on a zero-area triangle.
  void assemble(const Mesh& mesh, SparseMatrix& laplacian, Eigen::VectorXd& areas) const;

  //! The recorded triangles' vertex indices, face by face.
  const std::vector<std::array<int, 3>>& triangles() const { return triangles_; }

private:
  //! L's pattern and the slots, from triangles_.
  void build_pattern(Eigen::Index vertices);

  std::vector<std::array<int, 3>> triangles_;
  std::vector<std::array<int, 12>> slots_; //!< per corner c: (j,k), (k,j), (j,j), (k,k) in L's values
  SparseMatrix pattern_;
};

} // namespace sdflow
