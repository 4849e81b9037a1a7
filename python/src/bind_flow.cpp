//! The flow: parameters read by the scenario reader (run/parameters.h), the flow in memory
//! (SurfaceDiffusion, flow/surface_diffusion.h) and runs recorded in a run directory
//! (run_simulation / resume_simulation, run/simulation.h), with the GIL released while they work.

#include "arrays.h"
#include "bindings.h"

#include "sdflow/errors.h"
#include "sdflow/flow/surface_diffusion.h"
#include "sdflow/io/io.h"
#include "sdflow/io/repair.h"
#include "sdflow/limits.h"
#include "sdflow/log.h"
#include "sdflow/run/run_input.h"
#include "sdflow/run/simulation.h"

#include <fmt/format.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>

namespace sdflow::python {
namespace {

//! How the checks' messages name a surface given as arrays, as validation names it (arrays.h).
constexpr const char* surface_source = "arrays";

py::dict metrics_dict(long step, double time, double tau, const FlowMetrics& m, const std::string& event)
{
  py::dict d;
  d["step"] = step;
  d["time"] = time;
  d["tau"] = tau;
  d["vertices"] = m.vertices;
  d["faces"] = m.faces;
  d["components"] = m.components;
  d["genus"] = m.genus;
  d["area"] = m.area;
  d["volume"] = m.volume;
  d["mean_curvature"] = m.mean_curvature;
  d["curvature_deviation_pct"] = m.curvature_deviation_pct;
  d["d1"] = m.d1;
  d["d2"] = m.d2;
  d["debris_volume"] = m.debris_volume;
  d["event"] = event;
  d["energy"] = m.energy;
  return d;
}

py::list note_lines(const std::vector<FlowNote>& notes)
{
  py::list lines;
  for (const FlowNote& n : notes)
    lines.append(py::make_tuple(n.step, n.time, n.text, n.warning));
  return lines;
}

//! A step's event as the dict sdflow.Event is made from: kind, step, time, detail, rejections and,
//! for a re-triangulation's, its measures (RetriangulationMeasures; crossing_size None unless the
//! topology changed at a crossing).
py::dict event_dict(const StepEvent& e)
{
  py::dict d;
  d["kind"] = std::string(event_name(e.kind));
  d["step"] = e.step;
  d["time"] = e.time;
  d["detail"] = e.detail;
  d["rejections"] = e.rejections;
  if (e.kind == StepEventKind::refused)
    d["refusal"] = std::string(refusal_name(e.refusal));
  if (const auto& m = e.retriangulation) {
    d["crossing_pairs"] = m->crossing_pairs;
    d["crossing_size"] = std::isfinite(m->crossing_size) ? py::object(py::float_(m->crossing_size)) : py::none();
    d["components_before"] = m->before.components;
    d["components_after"] = m->after.components;
    d["genus_before"] = m->before.genus;
    d["genus_after"] = m->after.genus;
    d["boundary_loops_before"] = m->before.boundary_loops;
    d["boundary_loops_after"] = m->after.boundary_loops;
    d["faces_before"] = m->faces_before;
    d["faces_after"] = m->faces_after;
    d["faces_rebuilt"] = m->faces_rebuilt;
    d["volume_restored"] = m->volume_restored;
    d["debris_volume"] = m->debris_volume;
  }
  return d;
}

//! (step, time, tau, rejections, cg_iterations, factorised, events, notes): sdflow.Step's fields,
//! the events as event_dict makes them.
py::tuple step_tuple(const StepRecord& r, const std::vector<FlowNote>& notes)
{
  py::list events;
  for (const StepEvent& e : r.events)
    events.append(event_dict(e));
  return py::make_tuple(r.step, r.time, r.tau, r.rejections, r.cg_iterations, r.factorised, events,
                        note_lines(notes));
}

//! The flow in memory behind sdflow.Flow: a SurfaceDiffusion, the events and counters the Python
//! side reports, and the limits that advance() moves.
class FlowCore {
public:
  FlowCore(const py::handle& V, const py::handle& F, RunParameters parameters, bool force)
      : limits_(run_input_limits(FrontEnd::python, force)), run_(parameters)
  {
    BuiltMesh built = built_from_arrays(V, F);
    findings_ = std::move(built.findings);
    ToolboxLock lock;
    const CheckedFlowOptions checked(parameters); // once, before the input checks that read it
    check_run_input(built.mesh, parameters, surface_source, FrontEnd::python, limits_);
    // With the ℓ the input checks may have chosen (a thin part resolved).
    flow_ = std::make_unique<SurfaceDiffusion>(built.mesh, CheckedFlowOptions(parameters));
  }

  py::tuple step()
  {
    Busy busy(busy_);
    StepRecord record;
    std::vector<FlowNote> notes;
    {
      ToolboxLock lock;
      try {
        record = flow_->step();
      } catch (...) {
        pending_notes_ = flow_->take_notes(); // the reason's context, for failure_notes()
        throw;
      }
      notes = flow_->take_notes();
    }
    last_tau_ = record.tau;
    last_event_ = event_names(record.events);
    return step_tuple(record, notes);
  }

  //! Change the step and time limits; the flow continues from its state (bit for bit, as a resumed
  //! run does with a new --t-end), so that the last step lands on the new end time.
  void set_limits(long steps, double end_time)
  {
    const FlowOptions& current = flow_->options();
    if (current.steps == steps && current.end_time == end_time)
      return;
    Busy busy(busy_);
    FlowOptions p = current;
    p.steps = steps;
    p.end_time = end_time;
    ToolboxLock lock;
    const CheckedFlowOptions checked(p);
    check_end_time(flow_->mesh(), p.end_time, p.time_step.mode == TimeStepMode::constant ? p.time_step.tau : 0.0,
                   limits_, run_input_terms(FrontEnd::python));
    const FlowState state = flow_->state();
    rejected_before_ += flow_->rejected_trials();
    factorisations_before_ += flow_->factorisations();
    std::vector<FlowNote> notes = flow_->take_notes();
    flow_ = std::make_unique<SurfaceDiffusion>(state, checked);
    pending_notes_.insert(pending_notes_.end(), notes.begin(), notes.end());
  }

  py::list failure_notes() { return note_lines(std::exchange(pending_notes_, {})); }

  const SurfaceDiffusion& flow() const { return *flow_; }
  //! The run's parameters with the flow's options as resolved (ℓ and the refinement fixed).
  RunParameters parameters() const { return with_flow_options(run_, flow_->options()); }
  double last_tau() const { return last_tau_; }
  const std::string& last_event() const { return last_event_; }
  const std::vector<Finding>& findings() const { return findings_; }
  long rejected_trials() const { return rejected_before_ + flow_->rejected_trials(); }
  long factorisations() const { return factorisations_before_ + flow_->factorisations(); }

private:
  //! Refuses a second thread while one steps (the GIL is released meanwhile).
  struct Busy {
    explicit Busy(std::atomic<bool>& flag) : flag_(flag)
    {
      if (flag_.exchange(true))
        throw std::runtime_error("this Flow is already stepping in another thread");
    }
    ~Busy() { flag_ = false; }
    std::atomic<bool>& flag_;
  };

  SizeLimits limits_;
  RunParameters run_; // as given; the flow's options as resolved are the flow's
  std::unique_ptr<SurfaceDiffusion> flow_;
  std::vector<Finding> findings_;
  std::vector<FlowNote> pending_notes_;
  std::atomic<bool> busy_{false};
  double last_tau_ = 0;
  std::string last_event_;
  long rejected_before_ = 0, factorisations_before_ = 0;
};

//! Progress, stop requests and errors of a run: Python is called with the GIL taken back.
struct RunCallbacks {
  py::object progress; // None or a callable taking the step tuple
  std::optional<py::error_already_set> pending;
  bool stop = false;

  SimulationOptions options(const CheckedRunParameters& p)
  {
    SimulationOptions o{.parameters = p};
    o.progress = [this](const StepRecord& r) {
      py::gil_scoped_acquire acquire;
      if (progress.is_none() || stop)
        return;
      try {
        // A callback that answers True stops the run after this step, with a checkpoint.
        if (progress(step_tuple(r, {})).ptr() == Py_True)
          stop = true;
      } catch (py::error_already_set& e) {
        pending = std::move(e);
        stop = true;
      }
    };
    o.stop_requested = [this] {
      py::gil_scoped_acquire acquire;
      if (!stop && PyErr_CheckSignals() != 0) {
        pending = py::error_already_set();
        stop = true;
      }
      return stop;
    };
    return o;
  }

  //! After the run: re-raise a callback's exception, or a KeyboardInterrupt that says how to go on.
  void raise_pending(const SimulationResult& result, const std::filesystem::path& dir)
  {
    if (!pending)
      return;
    if (pending->matches(PyExc_KeyboardInterrupt) && result.interrupted) {
      PyErr_SetString(PyExc_KeyboardInterrupt,
                      fmt::format("stopped after step {} (t = {:.6g}) with a checkpoint; continue with "
                                  "sdflow.resume({})",
                                  result.steps, result.time, std::string(py::repr(py::str(dir.string()))))
                          .c_str());
      throw py::error_already_set();
    }
    throw *pending;
  }
};

py::dict result_dict(const SimulationResult& r)
{
  py::dict d;
  d["steps"] = r.steps;
  d["time"] = r.time;
  d["rejected_trials"] = r.rejected_trials;
  d["factorisations"] = r.factorisations;
  d["interrupted"] = r.interrupted;
  d["restarted"] = r.restarted;
  py::tuple vf = mesh_to_numpy(r.mesh);
  d["V"] = vf[0];
  d["F"] = vf[1];
  return d;
}

} // namespace

void bind_flow(py::module_& m)
{
  py::class_<RunParameters>(m, "RunParameters", "Every parameter of a run, as read from TOML (run/parameters.h).")
      .def("toml", &run_parameters_toml, "The fully resolved parameters as TOML, as run.toml holds them.")
      .def_property_readonly("steps", [](const RunParameters& p) { return p.steps; })
      .def_property_readonly("t_end", [](const RunParameters& p) { return p.end_time; })
      .def_property_readonly("input", [](const RunParameters& p) { return p.input.string(); })
      .def_property_readonly("out", [](const RunParameters& p) { return p.output_dir.string(); })
      .def_property_readonly("retriangulation",
                             [](const RunParameters& p) { return p.retriangulation.enabled; });

  m.def(
      "read_parameters",
      [](const std::vector<std::filesystem::path>& files) {
        RunParameters p;
        for (const auto& file : files)
          read_run_parameters(file, p);
        return p;
      },
      py::arg("files"), "RunParameters from TOML files read in order, each overriding the keys it has.");

  py::class_<FlowCore>(m, "FlowCore")
      .def(py::init<const py::handle&, const py::handle&, RunParameters, bool>(), py::arg("V"), py::arg("F"),
           py::arg("parameters"), py::arg("force"))
      .def("step", &FlowCore::step)
      .def("set_limits", &FlowCore::set_limits, py::arg("steps"), py::arg("t_end"))
      .def("failure_notes", &FlowCore::failure_notes)
      .def_property_readonly("finished", [](const FlowCore& c) { return c.flow().finished(); })
      .def_property_readonly("step_index", [](const FlowCore& c) { return c.flow().steps(); })
      .def_property_readonly("time", [](const FlowCore& c) { return c.flow().time(); })
      .def_property_readonly("tau", &FlowCore::last_tau)
      .def_property_readonly("steps_limit", [](const FlowCore& c) { return c.flow().options().steps; })
      .def_property_readonly("t_end", [](const FlowCore& c) { return c.flow().options().end_time; })
      .def_property_readonly("parameters", &FlowCore::parameters)
      .def_property_readonly("findings", [](const FlowCore& c) { return findings_to_python(c.findings()); })
      .def_property_readonly("rejected_trials", &FlowCore::rejected_trials)
      .def_property_readonly("factorisations", &FlowCore::factorisations)
      .def("V", [](const FlowCore& c) { return move_to_numpy(vertex_positions(c.flow().mesh())); })
      .def("F", [](const FlowCore& c) { return move_to_numpy(face_indices(c.flow().mesh())); })
      .def("N", [](const FlowCore& c) { return move_to_numpy(VertexVectors(c.flow().operators().normals)); })
      .def("H", [](const FlowCore& c) { return move_to_numpy(Eigen::VectorXd(c.flow().operators().curvature)); })
      .def("M", [](const FlowCore& c) { return move_to_numpy(Eigen::VectorXd(c.flow().operators().areas)); })
      .def("L", [](const FlowCore& c) { return move_to_scipy(SparseMatrix(c.flow().operators().laplacian)); })
      .def("w", [](const FlowCore& c) { return move_to_numpy(Eigen::VectorXd(c.flow().velocity())); })
      .def("metrics",
           [](const FlowCore& c) {
             const SurfaceDiffusion& f = c.flow();
             return metrics_dict(f.steps(), f.time(), c.last_tau(), f.metrics(), c.last_event());
           })
      .def("metrics_row", [](const FlowCore& c) {
        const SurfaceDiffusion& f = c.flow();
        return metrics_row(f.steps(), f.time(), c.last_tau(), f.metrics(), c.last_event());
      });

  m.attr("metrics_header") = metrics_header;

  m.def(
      "run_simulation",
      [](const py::object& V, const py::object& F, const CheckedRunParameters& checked, const py::object& progress,
         bool force) {
        RunParameters p = *checked;
        const SizeLimits limits = run_input_limits(FrontEnd::python, force);
        BuiltMesh built;
        if (V.is_none()) {
          ToolboxLock lock;
          built = p.repair ? read_mesh_or_repair(p.input) : read_mesh(p.input);
          for (const auto& f : built.findings)
            logger().warn("{}: {}", p.input.string(), f.message);
        } else {
          built = built_from_arrays(V, F);
        }
        const std::string source = V.is_none() ? p.input.string() : std::string(surface_source);
        {
          ToolboxLock lock;
          check_run_input(built.mesh, p, source, FrontEnd::python, limits);
        }
        RunCallbacks callbacks{.progress = progress};
        const std::filesystem::path dir = p.output_dir;
        SimulationResult result;
        {
          const SimulationOptions options = callbacks.options(CheckedRunParameters(p)); // ℓ as the checks chose
          ToolboxLock lock;
          result = run_simulation(built.mesh, options);
        }
        callbacks.raise_pending(result, dir);
        return result_dict(result);
      },
      py::arg("V"), py::arg("F"), py::arg("parameters"), py::arg("progress"), py::arg("force"));

  m.def(
      "resume_simulation",
      [](const CheckedRunParameters& checked, const py::object& progress, bool force) {
        const RunParameters& p = *checked;
        const SizeLimits limits = run_input_limits(FrontEnd::python, force);
        check_count(p.steps, limits.max_steps, "steps", limits);
        RunCallbacks callbacks{.progress = progress};
        const std::filesystem::path dir = p.output_dir;
        SimulationResult result;
        {
          const SimulationOptions options = callbacks.options(checked);
          ToolboxLock lock;
          result = resume_simulation(options);
        }
        callbacks.raise_pending(result, dir);
        return result_dict(result);
      },
      py::arg("parameters"), py::arg("progress"), py::arg("force"));

  py::class_<CheckedRunParameters>(m, "CheckedRunParameters",
                                   "RunParameters that validate_run_parameters accepted (run/parameters.h).");
  m.def(
      "validate_run_parameters", [](const RunParameters& p) { return CheckedRunParameters(p); },
      py::arg("parameters"), "The parameters checked once, for run_simulation or resume_simulation.");
  m.def(
      "set_output_dir", [](RunParameters& p, const std::filesystem::path& dir) { p.output_dir = dir; },
      py::arg("parameters"), py::arg("dir"));
  m.def(
      "set_limits",
      [](RunParameters& p, std::optional<long> steps, std::optional<double> t_end, std::optional<long> snapshot_every,
         std::optional<long> checkpoint_every) {
        if (steps) p.steps = *steps;
        if (t_end) p.end_time = *t_end;
        if (snapshot_every) p.snapshot_every = *snapshot_every;
        if (checkpoint_every) p.checkpoint_every = *checkpoint_every;
      },
      py::arg("parameters"), py::arg("steps"), py::arg("t_end"), py::arg("snapshot_every"),
      py::arg("checkpoint_every"));

  // For bench/python_overhead.py: the same flow stepped by the C++ API alone (no Python between
  // steps), from the same arrays and parameters; returns the wall seconds of construction + steps
  // and of the steps alone, and the final metrics row.
  m.def(
      "_cpp_flow_seconds",
      [](const py::handle& V, const py::handle& F, RunParameters p, long steps) {
        BuiltMesh built = built_from_arrays(V, F);
        ToolboxLock lock;
        using Clock = std::chrono::steady_clock;
        const auto start = Clock::now();
        SurfaceDiffusion flow(built.mesh, std::move(p));
        const auto constructed = Clock::now();
        StepRecord last;
        for (long i = 0; i < steps && !flow.finished(); ++i)
          last = flow.step();
        const auto end = Clock::now();
        const std::string row =
            metrics_row(flow.steps(), flow.time(), last.tau, flow.metrics(), event_names(last.events));
        return std::make_tuple(std::chrono::duration<double>(end - start).count(),
                               std::chrono::duration<double>(end - constructed).count(), row);
      },
      py::arg("V"), py::arg("F"), py::arg("parameters"), py::arg("steps"));
}

} // namespace sdflow::python
