#pragma once
//! \file arrays.h
//! \brief numpy arrays in and out of the toolbox's types.
//!
//! In: `V` is any (n, 3) array of reals, read in place when it is C-contiguous float64 (otherwise
//! converted once); `F` any (m, 3) array of integers (int32 and int64 read in place). A mesh is
//! built from them (an OpenMesh structure: that copy is the toolbox's own representation).
//! Out: results computed by the toolbox (Eigen matrices and vectors) are moved into a heap object
//! owned by a capsule, which becomes the numpy array's base: no element is copied.

#include "sdflow/geometry/laplacian.h"
#include "sdflow/mesh.h"
#include "sdflow/io/soup.h"
#include "sdflow/io/validate.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <mutex>
#include <utility>

namespace sdflow::python {

namespace py = pybind11;

//! Held while toolbox work runs without the GIL. The GIL is released first, then the toolbox
//! taken: one toolbox call at a time per process (docs/design.md §10: TetGen's predicates keep
//! global state, and running several flows at once is not supported), while other Python threads
//! run. A callback into Python from inside takes the GIL back (gil_scoped_acquire) without
//! deadlock, since no thread waits for the toolbox while holding the GIL.
class ToolboxLock {
public:
  ToolboxLock() : lock_(mutex()) {}
  static std::recursive_mutex& mutex();

private:
  py::gil_scoped_release release_;
  std::unique_lock<std::recursive_mutex> lock_;
};

//! An (n, 3) float64 array read in place, or its converted copy, kept alive with the view.
struct VertexArray {
  py::array_t<double, py::array::c_style | py::array::forcecast> array;
  Eigen::Map<const VertexVectors> view() const { return {array.data(), array.shape(0), 3}; }
};

//! `value` as (n, 3) float64 coordinates; throws InvalidParameter naming `name` on another shape
//! or a non-numeric dtype.
VertexArray vertex_array(const py::handle& value, const char* name = "V");

//! `value` as (m, 3) vertex indices; throws InvalidParameter naming `name` on another shape, a
//! non-integer dtype, or an index that does not fit an int.
FaceIndices face_array(const py::handle& value, const char* name = "F");

//! The polygon soup of V and F, as a reader would make it from a file.
PolygonSoup soup_from_arrays(const py::handle& V, const py::handle& F);

//! V and F validated and oriented as a file is when read (build_mesh, source "arrays"): what the
//! flow and the re-triangulation stages start from. Releases the GIL while it validates.
BuiltMesh built_from_arrays(const py::handle& V, const py::handle& F, const BuildOptions& options = {});

//! V and F validated as they are (not reoriented), vertex i being row i: what operators compute
//! on. Throws InvalidMesh (MeshValidationError, with the findings) on any validation error, and
//! when a vertex belongs to no triangle (it would be dropped, and the rows renumbered).
Mesh mesh_from_arrays(const py::handle& V, const py::handle& F);

//! Move an Eigen matrix or vector into a numpy array that owns it through a capsule.
template <typename Matrix>
py::array move_to_numpy(Matrix&& matrix)
{
  using M = std::decay_t<Matrix>;
  using Scalar = typename M::Scalar;
  static_assert(M::ColsAtCompileTime == 1 || M::IsRowMajor, "row-major matrices or vectors only");
  if (matrix.size() == 0) {
    if constexpr (M::ColsAtCompileTime == 1)
      return py::array_t<Scalar>(std::vector<py::ssize_t>{0});
    else
      return py::array_t<Scalar>(std::vector<py::ssize_t>{static_cast<py::ssize_t>(matrix.rows()),
                                                         static_cast<py::ssize_t>(matrix.cols())});
  }
  auto* owned = new M(std::forward<Matrix>(matrix));
  py::capsule owner(owned, [](void* p) { delete static_cast<M*>(p); });
  if constexpr (M::ColsAtCompileTime == 1)
    return py::array_t<Scalar>({static_cast<py::ssize_t>(owned->size())}, {static_cast<py::ssize_t>(sizeof(Scalar))},
                               owned->data(), owner);
  else
    return py::array_t<Scalar>({static_cast<py::ssize_t>(owned->rows()), static_cast<py::ssize_t>(owned->cols())},
                               {static_cast<py::ssize_t>(owned->cols() * sizeof(Scalar)),
                                static_cast<py::ssize_t>(sizeof(Scalar))},
                               owned->data(), owner);
}

//! (V, F) of a mesh: positions and triangles copied out of OpenMesh once, then moved into numpy.
py::tuple mesh_to_numpy(const Mesh& mesh);

//! A sparse matrix as scipy.sparse.csc_matrix sharing its data, indices and pointers (moved, not copied).
py::object move_to_scipy(SparseMatrix&& matrix);

//! Findings as a list of sdflow.Finding.
py::list findings_to_python(const std::vector<Finding>& findings);

} // namespace sdflow::python
