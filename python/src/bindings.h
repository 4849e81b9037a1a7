#pragma once
//! \file bindings.h
//! \brief The parts of the extension module sdflow._sdflow, one file each (module.cpp calls them).

#include <pybind11/pybind11.h>

namespace sdflow::python {

namespace py = pybind11;

void bind_errors(py::module_& m);   //!< the exception classes and the translation of the toolbox's
void bind_io(py::module_& m);       //!< read, write, validate, stats
void bind_repair(py::module_& m);   //!< repair of a file or of arrays, as `sdflow repair`
void bind_geometry(py::module_& m); //!< normals, curvatures, Laplacian, areas, measures
void bind_flow(py::module_& m);     //!< parameters, the flow in memory, runs
void bind_shapes(py::module_& m);   //!< the catalogue and formulas, meshed
void bind_retri(py::module_& m);    //!< the re-triangulation pipeline and its stages

} // namespace sdflow::python
