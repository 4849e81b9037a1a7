//! The toolbox's exceptions (errors.h, docs/design.md §9) as Python exceptions with the same
//! messages: bad input (exit code 2 on the command line) is a ValueError, a numerical failure
//! (exit code 3) an sdflow.NumericalError; every class carries the CLI's exit code as `exit_code`.

#include "arrays.h"
#include "bindings.h"

#include "sdflow/errors.h"
#include "sdflow/io/validate.h"

#include <cerrno>
#include <filesystem>

namespace sdflow::python {
namespace {

struct ExceptionTypes {
  PyObject* error = nullptr;
  PyObject* io_error = nullptr;
  PyObject* environment_failure = nullptr;
  PyObject* invalid_mesh = nullptr;
  PyObject* invalid_parameter = nullptr;
  PyObject* numerical_error = nullptr;
};
ExceptionTypes types; // created once by bind_errors, alive as long as the module

PyObject* make_type(py::module_& m, const char* name, const char* doc, std::initializer_list<PyObject*> bases,
                    int exit_code)
{
  py::tuple base_tuple(bases.size());
  std::size_t i = 0;
  for (PyObject* b : bases)
    base_tuple[i++] = py::reinterpret_borrow<py::object>(b);
  const std::string qualified = std::string("sdflow.") + name;
  PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, base_tuple.ptr(), nullptr);
  if (!type)
    throw py::error_already_set();
  py::handle(type).attr("exit_code") = exit_code;
  m.add_object(name, py::handle(type));
  return type;
}

void raise(PyObject* type, const char* message, const std::vector<Finding>* findings = nullptr)
{
  py::object instance = py::reinterpret_steal<py::object>(PyObject_CallFunction(type, "s", message));
  if (!instance)
    return; // the call set its own error
  instance.attr("findings") = findings ? findings_to_python(*findings) : py::list();
  PyErr_SetObject(type, instance.ptr());
}

} // namespace

void bind_errors(py::module_& m)
{
  py::class_<Finding>(m, "Finding", "A validation finding: severity (info, warning, error), stable code and message "
                                    "(codes: README, `sdflow stats`).")
      .def_property_readonly("severity", [](const Finding& f) { return severity_name(f.severity); })
      .def_readonly("code", &Finding::code)
      .def_readonly("message", &Finding::message)
      .def("__repr__", [](const Finding& f) {
        return "Finding(severity='" + std::string(severity_name(f.severity)) + "', code='" + f.code + "', message=" +
               std::string(py::repr(py::str(f.message))) + ")";
      });

  types.error = make_type(m, "Error", "Base of every sdflow exception (sdflow::Error).", {PyExc_Exception}, 1);
  types.io_error = make_type(m, "IoError", "A file cannot be read, parsed or written (file and line named).",
                             {types.error, PyExc_OSError, PyExc_ValueError}, 2);
  types.environment_failure =
      make_type(m, "EnvironmentFailure", "The disk or quota is full, a file size limit, a read-only file system.",
                {types.io_error}, 4);
  types.invalid_mesh = make_type(m, "InvalidMesh",
                                 "A mesh violates a precondition; `findings` lists validation findings with their codes.",
                                 {types.error, PyExc_ValueError}, 2);
  types.invalid_parameter =
      make_type(m, "InvalidParameter", "A parameter outside its documented range.", {types.error, PyExc_ValueError}, 2);
  types.numerical_error = make_type(m, "NumericalError",
                                    "A factorisation or solve failed, or a step stays unstable whatever τ (the "
                                    "command line's exit code 3; sdflow::SolverFailure).",
                                    {types.error, PyExc_RuntimeError}, 3);

  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p)
        std::rethrow_exception(p);
    } catch (const MeshValidationError& e) {
      raise(types.invalid_mesh, e.what(), &e.findings());
    } catch (const InvalidMesh& e) {
      raise(types.invalid_mesh, e.what());
    } catch (const InvalidParameter& e) {
      raise(types.invalid_parameter, e.what());
    } catch (const SolverFailure& e) {
      raise(types.numerical_error, e.what());
    } catch (const EnvironmentFailure& e) {
      raise(types.environment_failure, e.what());
    } catch (const IoError& e) {
      raise(types.io_error, e.what());
    } catch (const Error& e) {
      raise(types.error, e.what());
    } catch (const std::filesystem::filesystem_error& e) {
      const int error = e.code().value();
      const bool environment = error == ENOSPC || error == EDQUOT || error == EFBIG || error == EROFS || error == EIO;
      raise(environment ? types.environment_failure : types.io_error, e.what());
    }
  });
}

} // namespace sdflow::python
