//! The extension module sdflow._sdflow; the package sdflow (python/sdflow/__init__.py) wraps it.

#include "bindings.h"

#include "sdflow/errors.h"
#include "sdflow/log.h"

#include <pybind11/stl.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

PYBIND11_MODULE(_sdflow, m)
{
  m.doc() = "sdflow's C++ toolbox (surface diffusion flow on triangle meshes); use the package `sdflow`.";
  sdflow::python::bind_errors(m);
  sdflow::python::bind_io(m);
  sdflow::python::bind_repair(m);
  sdflow::python::bind_geometry(m);
  sdflow::python::bind_flow(m);
  sdflow::python::bind_shapes(m);
  sdflow::python::bind_retri(m);

  m.def(
      "log_to_stderr",
      [](const std::string& level) {
        const auto l = spdlog::level::from_str(level);
        if (l == spdlog::level::off && level != "off")
          throw sdflow::InvalidParameter("level must be \"debug\", \"info\", \"warn\", \"error\" or \"off\", got \"" +
                                         level + "\"");
        auto logger = std::make_shared<spdlog::logger>("sdflow", std::make_shared<spdlog::sinks::stderr_color_sink_mt>());
        logger->set_pattern("%^%l%$: %v");
        logger->set_level(l);
        sdflow::set_logger(logger);
      },
      pybind11::arg("level"));
}
