"""The flow: the same rows as `sdflow run`, bit for bit; a pinch-off; limits, callbacks, Ctrl-C;
run directories like the command line's, resumed bit for bit; parameters with the CLI's names,
checks and messages; numerical failures; the GIL released while stepping."""

import _thread
import os
import sys
import threading

import numpy as np
import pytest

import sdflow


FUZZ_RUN = os.path.join(os.environ.get("SDFLOW_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", "..")),
                        "tests", "data", "fuzz_run")


def cli_rows(cli, mesh, out, *flags):
    cli("run", "--input", mesh, "--out", out, "--quiet", *flags)
    with open(os.path.join(out, "metrics.csv")) as f:
        return f.read().splitlines()


def test_flow_rows_equal_the_command_lines_bit_for_bit(cli, meshes, tmp_path):
    expected = cli_rows(cli, meshes["dumbbell"], tmp_path / "cli", "--steps", 40, "--retriangulate")
    assert expected[0] == sdflow.metrics_header
    flow = sdflow.Flow(*sdflow.read(meshes["dumbbell"]), steps=40)  # re-triangulation on by default
    rows = [flow.metrics_row]
    while not flow.finished:
        flow.step()
        rows.append(flow.metrics_row)
    assert rows == expected[1:]
    assert any("remeshed" in row for row in rows), "the comparison covers re-triangulations"


def test_run_writes_the_command_lines_run_directory(cli, meshes, tmp_path):
    expected = cli_rows(cli, meshes["dumbbell"], tmp_path / "cli", "--steps", 25, "--retriangulate",
                        "--snapshot-every", 5)
    result = sdflow.run(meshes["dumbbell"], out=tmp_path / "py", steps=25, snapshot_every=5)
    with open(tmp_path / "py" / "metrics.csv") as f:
        assert f.read().splitlines() == expected
    for name in ("snapshots/step_000025.ply", "snapshots/step_000010.ply", "series.pvd"):
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    toml = [(tmp_path / d / "run.toml").read_text().splitlines() for d in ("cli", "py")]
    drop = ("input", "out")
    assert [l for l in toml[0] if not l.startswith(drop)] == [l for l in toml[1] if not l.startswith(drop)]
    assert result.steps == 25 and result.out == str(tmp_path / "py")
    np.testing.assert_array_equal(result.V, sdflow.read(tmp_path / "py" / "snapshots/step_000025.ply").V)


def test_run_from_arrays_and_resume_continue_bit_for_bit(meshes, tmp_path):
    V, F = sdflow.read(meshes["dumbbell"])
    sdflow.run(V, F, out=tmp_path / "whole", steps=30, checkpoint_every=5)
    stopped_at = []

    def stop_at_12(step):
        stopped_at.append(step.step)
        return step.step == 12  # True stops the run, with a checkpoint
    part = sdflow.run(V, F, out=tmp_path / "part", steps=30, checkpoint_every=5, callback=stop_at_12)
    assert part.interrupted and part.steps == 12
    rest = sdflow.resume(tmp_path / "part")
    assert rest.steps == 30
    assert (tmp_path / "part" / "metrics.csv").read_text() == (tmp_path / "whole" / "metrics.csv").read_text()


def test_ctrl_c_stops_a_run_with_a_checkpoint(meshes, tmp_path):
    V, F = sdflow.read(meshes["dumbbell"])

    def interrupt(step):
        if step.step == 7:
            _thread.interrupt_main()  # as Ctrl-C: SIGINT's handler
    with pytest.raises(KeyboardInterrupt, match="continue with sdflow.resume"):
        sdflow.run(V, F, out=tmp_path / "run", steps=20, callback=interrupt)
    assert sdflow.resume(tmp_path / "run").steps == 20
    sdflow.run(V, F, out=tmp_path / "whole", steps=20)
    assert (tmp_path / "run" / "metrics.csv").read_text() == (tmp_path / "whole" / "metrics.csv").read_text()


def test_run_refuses_a_directory_holding_a_run(meshes, tmp_path):
    sdflow.run(meshes["dumbbell"], out=tmp_path / "run", steps=2)
    with pytest.raises(sdflow.InvalidParameter, match="holds a run"):
        sdflow.run(meshes["dumbbell"], out=tmp_path / "run", steps=2)
    with pytest.raises(sdflow.InvalidParameter, match="no stop condition"):
        sdflow.run(meshes["dumbbell"], out=tmp_path / "other")
    with pytest.raises(sdflow.InvalidParameter, match="no run directory"):
        sdflow.run(meshes["dumbbell"], steps=2)


def test_flow_through_a_pinch_off(meshes):
    flow = sdflow.Flow(*sdflow.read(meshes["dumbbell"]), stop_at_topology_change=True)
    steps = flow.advance(t_end=1.0)
    last = steps[-1]
    assert flow.finished and last.topology_changed
    assert any(isinstance(e, sdflow.Split) for e in last.events)
    assert any(isinstance(e, sdflow.Surgery) for e in last.events)
    split = next(e for e in flow.events if isinstance(e, sdflow.Split))
    assert split.step == last.step and split.detail and "split" in last.event
    # What the re-triangulation measured comes with the event, not parsed from its log line.
    assert (split.components_before, split.components_after, split.genus_before, split.genus_after) == (1, 2, 0, 0)
    assert split.crossing_pairs > 0 and split.crossing_size is not None and split.crossing_size >= 0
    assert 0 < split.faces_rebuilt <= split.faces_before and split.faces_after == len(flow.F)
    surgery = next(e for e in last.events if isinstance(e, sdflow.Surgery))
    assert surgery.faces_rebuilt == split.faces_rebuilt and surgery.detail == split.detail
    assert all(e.crossing_pairs is None for e in flow.events if isinstance(e, sdflow.Rejected))
    assert 0.1 < last.time < 0.3
    assert flow.metrics["components"] == 2
    s = sdflow.stats(flow.V, flow.F, tetgen=False)
    assert s["component_count"] == 2 and all(c["closed"] and c["genus"] == 0 for c in s["components"])


def test_advance_lands_on_t_end_and_takes_steps(torus):
    flow = sdflow.Flow(*torus)
    flow.advance(0.05)
    assert flow.t == pytest.approx(0.05, rel=1e-12) and flow.finished and flow.t_end == 0.05
    assert flow.advance(0.04) == []
    flow.advance(0.08)
    assert flow.t == pytest.approx(0.08, rel=1e-12)
    taken = flow.advance(steps=3)
    assert [s.step for s in taken] == [flow.step_index - 2, flow.step_index - 1, flow.step_index]
    seen = []
    taken = flow.advance(1.0, callback=lambda s: seen.append(s.step) or len(seen) == 2)
    assert len(taken) == 2 and seen == [s.step for s in taken]
    with pytest.raises(sdflow.InvalidParameter, match="no stop condition"):
        sdflow.Flow(*torus).advance()
    limited = sdflow.Flow(*torus, steps=4)
    assert len(limited.advance()) == 4 and limited.finished
    limited.step()  # step() is not bounded by the limits
    assert limited.step_index == 5


def test_state_is_a_snapshot(torus):
    flow = sdflow.Flow(*torus)
    flow.step()
    state = flow.state
    assert isinstance(state, sdflow.State) and state.step == 1 and state.t == flow.t and state.tau == flow.tau
    assert state.metrics == flow.metrics and state.metrics["step"] == 1
    state.V[:] = 0
    assert np.abs(flow.V).max() > 0, "state arrays belong to the caller"
    assert not np.shares_memory(flow.V, flow.V), "each read is a fresh array"


def test_keyboard_interrupt_stops_advance_cleanly(meshes):
    """Ctrl-C arriving after the third step (simulated then, not after a wall time, so that the test
    does not depend on how fast the machine steps) stops advance at a consistent state."""
    flow = sdflow.Flow(*sdflow.read(meshes["ellipsoid"]), retriangulation=False)

    def interrupt_after_third(step):
        if step.step == 3:
            _thread.interrupt_main()

    with pytest.raises(KeyboardInterrupt):
        flow.advance(steps=10 ** 6, callback=interrupt_after_third)
    at = flow.step_index
    assert at >= 3 and flow.metrics["step"] == at
    flow.step()  # consistent: it goes on
    assert flow.step_index == at + 1


def test_the_gil_is_released_while_stepping(meshes):
    """Another Python thread runs while advance steps. With a switch interval far longer than the
    test, a thread keeps the GIL until it lets go of it itself, so the main thread can mark a step
    between two callbacks only if the step let go of the GIL: no speed enters."""
    V, F = sdflow.remesh(*sdflow.read(meshes["ellipsoid"]), edge_length=0.25, iterations=1)
    flow = sdflow.Flow(V, F, retriangulation=False)
    main_may_run, marked = threading.Event(), threading.Event()
    seen = []  # per step: whether the main thread ran during it
    done = False

    def callback(step):
        seen.append(marked.is_set())
        marked.clear()
        main_may_run.set()
        return seen[-1]  # stop once seen

    def work():
        nonlocal done
        main_may_run.set()
        try:
            flow.advance(steps=100, callback=callback)
        finally:
            done = True
            main_may_run.set()

    interval = sys.getswitchinterval()
    sys.setswitchinterval(100.0)
    try:
        worker = threading.Thread(target=work)
        worker.start()
        while True:
            main_may_run.wait()  # lets go of the GIL; takes it back only when the worker lets go
            main_may_run.clear()
            if done:
                break
            marked.set()
        worker.join()
    finally:
        sys.setswitchinterval(interval)
    # Holding the GIL through its steps, the worker would see no mark until advance returned.
    assert seen and seen[-1], seen
    assert flow.step_index == len(seen)


def test_numerical_failure_is_a_numerical_error_with_the_command_lines_message(cli, meshes, tmp_path):
    scenario = tmp_path / "unstable.toml"
    scenario.write_text("beta = 0\ntau = 0.5\nsteps = 20\n[retriangulation]\nenabled = false\n")
    result = cli("run", scenario, "--input", meshes["ellipsoid"], "--out", tmp_path / "cli", check=False)
    assert result.returncode == 3
    flow = sdflow.Flow(*sdflow.read(meshes["ellipsoid"]), scenario=scenario)
    with pytest.raises(sdflow.NumericalError) as e:
        flow.advance()
    assert e.value.exit_code == 3 and isinstance(e.value, RuntimeError) and sdflow.SolverFailure is sdflow.NumericalError
    assert f"sdflow: error: {e.value}\n" in result.stderr
    assert flow.step_index == 1, "the surface stays that of the last accepted step"


@pytest.mark.parametrize("key,value", [("beta", -1.0), ("curvature", "gauss"), ("mass", "lumped"),
                                       ("bogus", 1), ("steps", 1.5), ("adaptive", {"growth": "fast"}),
                                       ("retriangulation", {"every": 0}), ("time_step", "sometimes"),
                                       ("energy", {"kind": "formula", "formula": "1 - 0.9 * (nx^4 + ny^4 + nz^4)"})])
def test_parameters_are_checked_with_the_scenario_readers_messages(cli, meshes, tmp_path, key, value):
    V, F = sdflow.read(meshes["ellipsoid"])
    with pytest.raises(sdflow.InvalidParameter) as e:
        sdflow.Flow(V, F, **{key: value})
    assert isinstance(e.value, ValueError) and e.value.exit_code == 2
    from sdflow._parameters import to_toml
    scenario = tmp_path / "s.toml"
    scenario.write_text(to_toml({key: value, "steps": 1} if key != "steps" else {key: value})[0])
    stderr = cli("run", scenario, "--input", meshes["ellipsoid"], "--out", tmp_path / "o", check=False).stderr
    message = str(e.value)
    if message.startswith("keyword argument "):
        where, message = message[len("keyword argument "):].split(": ", 1)
    assert message in stderr, (message, stderr)


def test_parameter_names_and_defaults(torus, tmp_path):
    V, F = torus
    p = sdflow.Flow(V, F).parameters
    assert p["retriangulation"]["enabled"] is True, "re-triangulation on by default"
    assert p["retriangulation"]["edge_length"] == pytest.approx(sdflow.mean_edge_length(V, F), rel=1e-12)
    assert p["curvature"] == "cotangent" and p["beta"] == 0.5 and p["time_step"] == "adaptive"
    assert sdflow.Flow(V, F, retriangulation=False).parameters["retriangulation"]["enabled"] is False
    assert sdflow.Flow(V, F, preset="paper").parameters["curvature"] == "normal_integral"
    q = sdflow.Flow(V, F, tau=0.01, adaptive={"growth": 1.5}, retriangulation={"edges_per_radius": 0},
                    reference_sphere={"centre": [1, 2, 3], "radius": 2}).parameters
    assert q["time_step"] == "constant" and q["tau"] == 0.01 and q["adaptive"]["growth"] == 1.5
    assert q["retriangulation"]["edges_per_radius"] == 0 and q["reference_sphere"]["centre"] == [1, 2, 3]
    scenario = tmp_path / "s.toml"
    scenario.write_text('beta = 0.75\ncurvature = "normal_integral"\n[retriangulation]\nenabled = false\n')
    r = sdflow.Flow(V, F, scenario=scenario, beta=1.0).parameters
    assert r["beta"] == 1.0 and r["curvature"] == "normal_integral" and r["retriangulation"]["enabled"] is False
    with pytest.raises(sdflow.InvalidParameter, match="in memory"):
        sdflow.Flow(V, F, out="somewhere")


def test_run_and_flow_refuse_overlapping_bodies_before_step_1_and_say_what_joins_them(cli, tmp_path):
    """The checks of `sdflow run` (run/run_input.h) in Python's words: two spheres that overlap
    are refused before step 1 instead of failing inside the re-triangulation, and what the
    message advises runs."""
    path = os.path.join(FUZZ_RUN, "two_overlapping_spheres_read_as_body_and_cavity.off")
    refused = cli("run", "--input", path, "--out", tmp_path / "cli", "--steps", 2, "--quiet", check=False)
    assert refused.returncode == 2 and "the bodies overlap" in refused.stderr
    with pytest.raises(sdflow.InvalidMesh, match="components 0 and 1 cross each other") as from_file:
        sdflow.run(path, out=tmp_path / "file", steps=2)
    assert "the bodies overlap" in str(from_file.value) and "sdflow.retriangulate(V, F)" in str(from_file.value)
    assert from_file.value.exit_code == 2
    assert not os.path.exists(tmp_path / "file" / "metrics.csv")
    V, F = sdflow.read(path)
    with pytest.raises(sdflow.InvalidMesh, match="^arrays: components 0 and 1 cross each other"):
        sdflow.run(V, F, out=tmp_path / "arrays", steps=2)
    with pytest.raises(sdflow.InvalidMesh, match="the bodies overlap"):
        sdflow.Flow(V, F)
    joined = sdflow.Flow(*sdflow.retriangulate(V, F))
    assert len(joined.advance(steps=2)) == 2


def test_run_and_flow_refuse_a_vertex_far_from_the_others_and_absurd_end_times():
    """An octahedron with a vertex at 10⁹, which `stats` refuses, is refused by run and Flow with
    the finding and Python's remedy; an end time beyond the plausibility limit names `end_time`
    and `force=True`, in the constructor and in advance."""
    V = np.array([[1e9, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], dtype=float)
    F = np.array([[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]])
    for call in (lambda: sdflow.Flow(V, F, retriangulation=False),
                 lambda: sdflow.run(V, F, out="unused", steps=2, retriangulation=False)):
        with pytest.raises(sdflow.InvalidMesh, match="a vertex far from the others") as e:
            call()
        assert "sdflow.repair(V, F, merge_tolerance=" in str(e.value)
    V, F = sdflow.shape("sphere", vertices=200)
    with pytest.raises(sdflow.InvalidParameter, match="^end_time=1e\\+308 is more than") as e:
        sdflow.Flow(V, F, t_end=1e308)
    assert "or force=True" in str(e.value)
    flow = sdflow.Flow(V, F, retriangulation=False)
    with pytest.raises(sdflow.InvalidParameter, match="^end_time=1e\\+308 is more than"):
        flow.advance(t_end=1e308)
    assert flow.step_index == 0
    forced = sdflow.Flow(V, F, retriangulation=False, t_end=1e308, steps=2, force=True)
    assert len(forced.advance()) == 2


def test_flow_refines_a_cube_too_coarse_for_its_mean_edge_length_and_keeps_an_edge_length_given():
    """A cube of 8 vertices with no edge length given is refined exactly before step 1, as `sdflow
    run` refines it (the same volume, 1, to rounding), and runs; given that edge length, it is
    refused as too coarse for it."""
    V = np.array([[x, y, z] for z in (-0.5, 0.5) for y in (-0.5, 0.5) for x in (-0.5, 0.5)], dtype=float)
    F = np.array([[0, 6, 2], [0, 4, 6], [1, 3, 7], [1, 7, 5], [0, 1, 5], [0, 5, 4],
                  [2, 7, 3], [2, 6, 7], [0, 3, 1], [0, 2, 3], [4, 5, 7], [4, 7, 6]])
    flow = sdflow.Flow(V, F)
    assert len(flow.V) > 300
    assert flow.metrics["volume"] == pytest.approx(1.0, abs=1e-13)
    assert len(flow.advance(steps=2)) == 2
    with pytest.raises(sdflow.InvalidParameter, match="fewer than the 20 it needs"):
        sdflow.Flow(V, F, retriangulation={"edge_length": 1.0})


def test_a_film_off_its_substrate_is_refused_in_pythons_words():
    """`boundary="substrate"` takes a film whose contact lines lie on the plane; lifted off it, Flow and
    run refuse it before step 1, naming the loop and the keyword as Python writes it."""
    V, F = sdflow.shape("cuboid-island", a=2, b=1, c=0.5, radius=0.2, edge_length=0.15)
    flow = sdflow.Flow(V, F, boundary="substrate", substrate={"contact_angle": 60})
    assert len(flow.advance(steps=2)) == 2
    for call in (lambda: sdflow.Flow(V, F, boundary="substrate", substrate={"z": 0.25}),
                 lambda: sdflow.run(V, F, out="unused", steps=2, boundary="substrate", substrate={"z": 0.25})):
        with pytest.raises(sdflow.InvalidParameter, match="boundary loop 0") as e:
            call()
        assert 'is not on the plane (substrate={"z": 0.25})' in str(e.value)
        assert e.value.exit_code == 2
