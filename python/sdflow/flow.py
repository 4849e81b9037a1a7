"""The flow in memory (`Flow`, over the C++ `SurfaceDiffusion`) and runs recorded in a run
directory (`run`, `resume`), as `sdflow run` records them."""

import math
import os
import tomllib
from dataclasses import dataclass
from typing import NamedTuple

from . import _parameters, _sdflow
from ._progress import make_progress


@dataclass(frozen=True)
class Event:
    """Something that happened in a step besides the step itself (metrics.csv's `event` column).

    `kind` is one of "start", "rejected", "fallback", "remeshed", "surgery", "split", "merged",
    "cleaned", "refused", "touchdown", "contact"; `detail` is the re-triangulation's line of events.log for
    "remeshed" to "cleaned", "touchdown" and "contact", and "refused" (why it was refused), the reason for
    "fallback". "touchdown" (a film reached its substrate and was cut there) and "contact" (two contact
    lines met) carry in `crossing_size` the film's height or the contact lines' gap that triggered them. A re-triangulation's events carry
    what it measured: the face pairs that crossed before it (`crossing_pairs`), the narrowest neck or
    gap within 2ℓ of them, at the start of the step that crossed, where the topology changed (`crossing_size`,
    else None), the components, genus and
    boundary loops before and after, the faces before, after and rebuilt, the relative volume
    change the restoration made and the volume dropped as debris. Other events leave them None.
    A "refused" event names why in `refusal`: "topology-without-crossing" (a topology change where
    the surface did not cross itself), "topology-beyond-crossings" (a change larger than, or away
    from, what the crossings explain), "remeshing-crossed" (the remeshing kept making crossings
    of its own and nothing was rebuilt), "nothing-kept" (the pipeline left no surface it could
    keep, which is never the flow's: it keeps each body's volume) or "volume-not-kept" (at a
    crossing, the rebuild changed the material volume by more than a twentieth). A crossing whose
    rebuild is refused is capped instead when that works: a "surgery" event whose detail says
    "so the crossings were capped".
    """
    kind: str
    step: int
    time: float
    detail: str = ""
    rejections: int = 0
    crossing_pairs: int | None = None
    crossing_size: float | None = None
    components_before: int | None = None
    components_after: int | None = None
    genus_before: int | None = None
    genus_after: int | None = None
    boundary_loops_before: int | None = None
    boundary_loops_after: int | None = None
    faces_before: int | None = None
    faces_after: int | None = None
    faces_rebuilt: int | None = None
    volume_restored: float | None = None
    debris_volume: float | None = None
    refusal: str | None = None


class Start(Event):
    """A start step: τ taken on stability alone while the mesh does not resolve the curvature."""


class Rejected(Event):
    """Trial steps were rejected before the accepted one (τ was reduced)."""


class Remeshed(Event):
    """The triangulation was improved (same topology)."""


class Surgery(Event):
    """Self-intersections were removed and the surface rebuilt (a pinch-off, a seal, bodies touching)."""


class Split(Event):
    """A component broke into several (a pinch-off)."""


class Merged(Event):
    """Components were joined."""


class Cleaned(Event):
    """Components too small to flow were dropped as debris (`debris_volume` says how much)."""


class Refused(Event):
    """A re-triangulation was refused, the surface kept (`refusal` says why)."""


class Touchdown(Event):
    """A film on a substrate came within the threshold of it away from its contact lines and was cut
    there: a hole opened, or an island broke (`crossing_size`: the film's lowest height)."""


class Contact(Event):
    """Two contact lines on a substrate came within the threshold of each other: islands merged, or
    an island's footprint pinched and it broke (`crossing_size`: their gap)."""


class Fallback(Event):
    """A τ table's step failed even after its halvings: adaptive steps covered its τ of time."""


_EVENT_TYPES = {"start": Start, "rejected": Rejected, "remeshed": Remeshed, "surgery": Surgery, "split": Split,
                "merged": Merged, "cleaned": Cleaned, "fallback": Fallback, "refused": Refused,
                "touchdown": Touchdown, "contact": Contact}


@dataclass(frozen=True)
class Step:
    """One accepted step: its index, the time reached, τ, rejected trials, CG iterations, whether
    it factorised, its events and the flow's notes (rejected trials, re-triangulations)."""
    step: int
    time: float
    tau: float
    rejections: int
    cg_iterations: int
    factorised: bool
    events: tuple = ()
    notes: tuple = ()

    @property
    def event(self):
        """The events joined by '+', as metrics.csv writes them."""
        return "+".join(e.kind for e in self.events)

    @property
    def topology_changed(self):
        """A split or a merge happened (a seal changes the genus: see the metrics)."""
        return any(isinstance(e, (Split, Merged)) for e in self.events)


def _notes(raw):
    return tuple(f"step {s} t={t}: {text}" for s, t, text, _ in raw)


def _step(raw):
    step, time, tau, rejections, cg, factorised, events, notes = raw
    events = tuple(_EVENT_TYPES.get(e["kind"], Event)(**e) for e in events)
    return Step(step, time, tau, rejections, cg, factorised, events, _notes(notes))


class State(NamedTuple):
    """A snapshot of the flow: arrays (copied out of the flow, theirs to keep), time, τ of the last
    step, step index and the metrics row (metrics.csv's columns)."""
    V: object
    F: object
    t: float
    tau: float
    step: int
    metrics: dict


class Flow:
    """Surface diffusion flow of a surface in memory: the C++ `SurfaceDiffusion`.

    ``Flow(V, F, **parameters)``: V (n×3 reals), F (m×3 integers), validated and oriented as a mesh
    file is when read (`findings` has what was found). Parameters are the scenario keys of
    `sdflow run` (toolbox/sdflow/run/parameters.h) with their defaults, names, checks and
    messages: ``beta``, ``curvature``, ``mass``, ``tau``, ``time_step``, ``extrapolate``,
    ``conserve_volume``, ``boundary``, ``steps``, ``t_end``, ``adaptive={...}``,
    ``retriangulation={...}``, ``preset``, ... Re-triangulation is **on** by default
    (``retriangulation=False`` turns it off); its ℓ defaults to the initial mean edge length.
    ``scenario=`` reads a TOML scenario first (keyword arguments override it).

    The surface and parameters get the checks of `sdflow run` before step 1 (InvalidMesh,
    InvalidParameter): bodies that overlap, a vertex far from the others, a surface too coarse to
    re-triangulate at an edge length given, an absurd end time. With no edge length given, a surface
    too coarse at its mean edge length is refined first, exactly, as `sdflow run` does. force=True
    skips the plausibility limits (as --force).
    """

    def __init__(self, V, F, *, scenario=None, force=False, **parameters):
        for key in ("input", "out"):
            if key in parameters:
                raise _sdflow.InvalidParameter(
                    f"keyword argument {key}: a Flow holds its surface in memory; sdflow.run() reads "
                    "`input` and writes `out`")
        p = _parameters.read(parameters, scenario=scenario)
        self._core = _sdflow.FlowCore(V, F, p, bool(force))
        self._limits = (self._core.steps_limit, self._core.t_end)
        self.events = []
        """Every event so far, in order."""

    # -- stepping -----------------------------------------------------------------------------
    def step(self):
        """Take one accepted step (the GIL is released meanwhile) and return its `Step`. The limits
        (steps, t_end) bound `advance`, not `step`: a finished flow is stepped further.

        Raises sdflow.NumericalError when the flow cannot go on stably; the surface stays that of
        the last accepted step, and the exception's `notes` hold the flow's notes before it.
        """
        if self._core.finished:
            self._core.set_limits(0, math.inf)
        try:
            record = _step(self._core.step())
        except _sdflow.Error as e:
            e.notes = _notes(self._core.failure_notes())
            raise
        self.events.extend(record.events)
        return record

    def advance(self, t_end=None, *, steps=None, callback=None, progress=False):
        """Step until time `t_end` (the last step lands on it) and/or for `steps` more steps; with
        neither, until the limits given to the constructor (steps, t_end, stop_at_topology_change).
        Returns the list of `Step` records taken.

        callback(step) is called after every step; returning True stops. progress=True shows a
        bar (tqdm when installed, else a line on stderr); a callable is called like callback.
        Ctrl-C (KeyboardInterrupt) stops after the step under way: the flow stays consistent at
        the last accepted step and can be advanced again.

        A new t_end continues the flow from its state with that end time, as ``sdflow run
        --resume --t-end`` does (bit for bit; the reused factorisation is rebuilt once).
        """
        core = self._core
        if t_end is None and steps is None:
            limit_steps, limit_time = self._limits
            if limit_steps == 0 and math.isinf(limit_time):
                raise _sdflow.InvalidParameter("no stop condition: give a number of steps or an end time")
            core.set_limits(limit_steps, limit_time)
        else:
            if t_end is not None and not float(t_end) > core.time:
                return []
            core.set_limits(0, float(t_end) if t_end is not None else math.inf)
        bar = make_progress(progress, t_start=core.time, t_end=core.t_end,
                            steps=steps if steps is not None else
                            (core.steps_limit - core.step_index if core.steps_limit else None))
        taken = []
        try:
            while not core.finished and (steps is None or len(taken) < steps):
                record = self.step()
                taken.append(record)
                bar.update(record)
                if callback is not None and callback(record) is True:
                    break
        finally:
            bar.close()
        return taken

    # -- state --------------------------------------------------------------------------------
    @property
    def finished(self):
        """The limits in effect are reached (the constructor's, or the last advance's), or
        (stop_at_topology_change) the topology changed."""
        return self._core.finished

    @property
    def t(self):
        """The time reached."""
        return self._core.time

    @property
    def tau(self):
        """τ of the last step (0 before the first)."""
        return self._core.tau

    @property
    def step_index(self):
        """Index of the last accepted step (0 at the start)."""
        return self._core.step_index

    @property
    def t_end(self):
        """The end time in effect (inf: none): the constructor's, or the last advance's."""
        return self._core.t_end

    @property
    def V(self):
        """Vertex positions (n×3 float64), a copy the caller owns."""
        return self._core.V()

    @property
    def F(self):
        """Triangles (m×3 int32), a copy the caller owns."""
        return self._core.F()

    @property
    def N(self):
        """Unit normals of the current surface (eq. 8), as the next step uses them."""
        return self._core.N()

    @property
    def H(self):
        """Mean curvature of the current surface, as the next step uses it (the `curvature` option)."""
        return self._core.H()

    @property
    def L(self):
        """The cotangent matrix L of the current surface (scipy.sparse.csc_matrix)."""
        return self._core.L()

    @property
    def M(self):
        """The vertex areas of Δ = M⁻¹L (the `mass` option)."""
        return self._core.M()

    @property
    def w(self):
        """w of the last step (the normal velocity is −w); zeros at the start and after a re-triangulation."""
        return self._core.w()

    @property
    def metrics(self):
        """The current row of metrics.csv as a dict (step, time, tau, vertices, ..., event)."""
        return self._core.metrics()

    @property
    def metrics_row(self):
        """The current line of metrics.csv (without its newline), exactly as `sdflow run` writes it."""
        return self._core.metrics_row().rstrip("\n")

    @property
    def state(self):
        """`State(V, F, t, tau, step, metrics)`."""
        m = self.metrics
        return State(self.V, self.F, self.t, self.tau, self.step_index, m)

    @property
    def parameters(self):
        """Every parameter as resolved (ℓ fixed), as a dict of run.toml's keys."""
        return tomllib.loads(self._core.parameters.toml())

    @property
    def findings(self):
        """What validating the initial V, F found (sdflow.Finding list)."""
        return self._core.findings

    @property
    def rejected_trials(self):
        return self._core.rejected_trials

    @property
    def factorisations(self):
        return self._core.factorisations

    def __repr__(self):
        m = self.metrics
        return (f"<sdflow.Flow step {m['step']} t={m['time']:.6g}: {m['vertices']} vertices, "
                f"{m['components']} component(s), genus {m['genus']}>")


class RunResult(NamedTuple):
    """What `run` and `resume` return: the final surface and the run's counters."""
    V: object
    F: object
    steps: int
    time: float
    rejected_trials: int
    factorisations: int
    interrupted: bool
    restarted: bool
    out: str


def _run_callback(progress, callback, p, t_start=0.0):
    bar = make_progress(progress, t_start=t_start, t_end=p.t_end, steps=p.steps or None)

    def on_step(raw):
        record = _step(raw)
        bar.update(record)
        return callback is not None and callback(record) is True
    return on_step, bar


def _result(d, out):
    return RunResult(d["V"], d["F"], d["steps"], d["time"], d["rejected_trials"], d["factorisations"],
                     d["interrupted"], d["restarted"], out)


def run(V=None, F=None, *, scenario=None, progress=False, callback=None, force=False, **parameters):
    """Run the flow into a run directory, exactly as `sdflow run` does (metrics.csv, timings.csv, snapshots,
    series.pvd, run.toml, events.log, checkpoint.bin); returns a `RunResult`.

    The surface: V, F arrays, or ``input=MESH`` (or `input` in the scenario). ``out=DIR`` (or `out`
    in the scenario) names the directory, which must not hold a run. Parameters as for `Flow`
    (re-triangulation on by default) and a stop condition (``steps`` or ``t_end``).
    callback(step) after every step (True: stop, with a checkpoint; `resume` continues).
    Ctrl-C stops after the step under way with a checkpoint and raises KeyboardInterrupt.
    force=True skips the plausibility limits (as --force).
    """
    if isinstance(V, (str, os.PathLike)):
        if F is not None:
            raise _sdflow.InvalidParameter("give V, F arrays or a mesh path, not both")
        parameters["input"], V = V, None
    p = _parameters.read(parameters, scenario=scenario)
    if V is None and not p.input:
        raise _sdflow.InvalidParameter("no input mesh: give V, F, input=MESH or `input` in the scenario file")
    if V is not None and F is None:
        raise _sdflow.InvalidParameter("F is missing: give V and F")
    if not p.out:
        raise _sdflow.InvalidParameter("no run directory: give out=DIR or `out` in the scenario file")
    checked = _sdflow.validate_run_parameters(p)  # once, before the input is read
    on_step, bar = _run_callback(progress, callback, p)
    try:
        d = _sdflow.run_simulation(V, F, checked, on_step, force)
    finally:
        bar.close()
    return _result(d, p.out)


def resume(out, *, steps=None, t_end=None, snapshot_every=None, checkpoint_every=None, progress=False,
           callback=None, force=False):
    """Continue the run in `out` from its checkpoint, bit for bit, as ``sdflow run --resume`` does;
    only the limits (steps, t_end) and the snapshot and checkpoint intervals may change."""
    toml = os.path.join(os.fspath(out), "run.toml")
    if not os.path.exists(toml):
        raise _sdflow.InvalidParameter(
            f"{os.fspath(out)} holds no run to resume (no run.toml: it was stopped before writing anything, or is "
            "not a run directory); start the run again with out=")
    p = _sdflow.read_parameters([toml])
    _sdflow.set_output_dir(p, os.fspath(out))
    _sdflow.set_limits(p, steps, t_end, snapshot_every, checkpoint_every)
    checked = _sdflow.validate_run_parameters(p)
    on_step, bar = _run_callback(progress, callback, p)
    try:
        d = _sdflow.resume_simulation(checked, on_step, force)
    finally:
        bar.close()
    return _result(d, os.fspath(out))
