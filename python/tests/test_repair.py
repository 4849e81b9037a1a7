"""`sdflow.repair`: the same repairs, counts, messages, mesh and errors as `sdflow repair --json`."""

import inspect
import json

import numpy as np
import pytest

import sdflow


def ellipsoid():
    return sdflow.shape("ellipsoid", vertices=800)


def seam_soup(V, F, offset=0.0):
    """V, F cut along a seam: the faces whose centroid has x > 0 get their own copies of the
    vertices they share with the others (moved by `offset`). Returns (V2, F2, seam vertex count)."""
    right = V[F].mean(axis=1)[:, 0] > 0
    seam = np.intersect1d(F[right], F[~right])
    number = np.arange(len(V))
    number[seam] = len(V) + np.arange(len(seam))
    F2 = F.copy()
    F2[right] = number[F[right]]
    return np.vstack([V, V[seam] + offset]), F2, len(seam)


def write_off(path, V, F):
    """An OFF text of any soup (sdflow.write refuses invalid meshes); repr() round-trips floats."""
    with open(path, "w") as f:
        f.write(f"OFF\n{len(V)} {len(F)} 0\n")
        f.writelines(" ".join(repr(float(x)) for x in p) + "\n" for p in V)
        f.writelines(f"{len(t)} " + " ".join(str(int(i)) for i in t) + "\n" for t in F)


def read_off(path):
    """The positions and faces of an OFF file exactly as written (no validation, no reorientation)."""
    with open(path) as f:
        lines = [line for line in f.read().splitlines() if line and not line.startswith("#")]
    n, m, _ = map(int, lines[1].split())
    V = np.array([[float(x) for x in line.split()] for line in lines[2:2 + n]])
    F = np.array([[int(x) for x in line.split()[1:]] for line in lines[2 + n:2 + n + m]])
    return V, F


def codes_and_counts(info):
    return [(r["code"], r["count"]) for r in info["repairs"]]


def consistently_oriented_and_closed(F):
    """Every directed edge once, and its reverse present: one orientation on a closed surface."""
    edges = {(int(a), int(b)) for t in F for a, b in zip(t, np.roll(t, -1))}
    return len(edges) == 3 * len(F) and all((b, a) in edges for a, b in edges)


def test_duplicated_seam_is_repaired_as_the_command_line_does(cli, tmp_path):
    V, F = ellipsoid()
    V2, F2, seam = seam_soup(V, F)
    soup = tmp_path / "seam.off"
    write_off(soup, V2, F2)
    out = tmp_path / "repaired.off"
    expected = json.loads(cli("repair", soup, "-o", out, "--json").stdout)
    V_cli, F_cli = read_off(out)

    from_file = sdflow.repair(soup)
    assert from_file.info == {k: v for k, v in expected.items() if k != "output"}
    from_arrays = sdflow.repair(V2, F2)
    assert codes_and_counts(from_arrays.info) == codes_and_counts(expected) == [("duplicate-vertex", seam)]
    assert from_arrays.info["repairs"][0]["message"].startswith("arrays: ")
    for result in (from_file, from_arrays):
        np.testing.assert_array_equal(result.V, V_cli)
        np.testing.assert_array_equal(result.F, F_cli)
    # The copies merge into the first vertex at each point: the mesh before the cut comes back.
    np.testing.assert_array_equal(from_arrays.V, V)
    np.testing.assert_array_equal(from_arrays.F, F)


def test_merge_tolerance_closes_a_seam_whose_copies_moved(tmp_path):
    V, F = ellipsoid()
    V2, F2, seam = seam_soup(V, F, offset=1e-12)
    apart = sdflow.repair(V2, F2)
    assert apart.info["repairs"] == [] and "has-boundary" in [f["code"] for f in apart.info["findings"]]
    closed = sdflow.repair(V2, F2, merge_tolerance=1e-9)
    assert codes_and_counts(closed.info) == [("duplicate-vertex", seam)] and closed.info["findings"] == []
    np.testing.assert_array_equal(closed.F, F)
    with pytest.raises(sdflow.InvalidParameter, match="merge tolerance must be in"):
        sdflow.repair(V2, F2, merge_tolerance=0.5)


def test_flipped_faces_come_back_consistently_oriented_and_outward():
    V, F = ellipsoid()
    flipped = F.copy()
    some = np.arange(0, len(F), 37)
    flipped[some] = flipped[some, ::-1]
    result = sdflow.repair(V, flipped)
    assert codes_and_counts(result.info) == [("inconsistent-orientation", len(some))]
    assert consistently_oriented_and_closed(result.F)
    assert sdflow.volume(*result) == pytest.approx(sdflow.volume(V, F), rel=1e-12) and sdflow.volume(*result) > 0

    inside_out = sdflow.repair(V, F[:, ::-1])
    assert codes_and_counts(inside_out.info) == [("orientation-flipped", 1)]
    assert sdflow.volume(*inside_out) == pytest.approx(sdflow.volume(V, F), rel=1e-12)


def flat_tetrahedron():
    """A closed surface that bounds nothing: a tetrahedron's faces on the corners of a square."""
    V = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], float)
    F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    return V, F


def test_what_no_repair_fixes_raises_the_command_lines_error(cli, tmp_path):
    V, F = flat_tetrahedron()
    path = tmp_path / "flat.off"
    write_off(path, V, F)
    refused = cli("repair", path, "-o", tmp_path / "out.off", "--json", check=False)
    assert refused.returncode == 2
    with pytest.raises(ValueError) as from_file:
        sdflow.repair(path)
    assert refused.stderr.strip() == f"sdflow: error: {from_file.value}"
    assert isinstance(from_file.value, sdflow.InvalidMesh) and from_file.value.exit_code == 2
    expected = json.loads(refused.stdout)
    assert expected["message"] == str(from_file.value) and expected["exit_code"] == from_file.value.exit_code
    assert [(f.severity, f.code, f.message) for f in from_file.value.findings] == \
        [(f["severity"], f["code"], f["message"]) for f in expected["findings"]]
    assert [f.code for f in from_file.value.findings] == ["zero-volume-component"]

    with pytest.raises(sdflow.InvalidMesh, match="^arrays: ") as from_arrays:
        sdflow.repair(V, F)
    assert str(from_arrays.value).replace("arrays", str(path)) == str(from_file.value)


@pytest.mark.parametrize("V,F,code", [
    (flat_tetrahedron()[0], np.array([[0, 1, 4]]), "face-index-out-of-range"),
    (np.array([[0, 0, 0], [1, 0, 0], [np.nan, 1, 0]]), np.array([[0, 1, 2]]), "non-finite-coordinate"),
    (np.zeros((3, 3)), np.zeros((0, 3), int), "empty-mesh"),
])
def test_unrepairable_arrays_raise_value_error_with_the_finding(V, F, code):
    with pytest.raises(ValueError) as error:
        sdflow.repair(V, F)
    assert code in [f.code for f in error.value.findings]


def test_self_intersections_are_counted_and_removed_on_request():
    V, F = sdflow.shape("sphere", vertices=300)
    crossing = (np.vstack([V, V + [1.0, 0, 0]]), np.vstack([F, F + len(V)]))
    kept = sdflow.repair(*crossing)
    assert kept.info["self_intersecting_pairs"] == len(sdflow.intersections(*kept)) > 0
    assert kept.info["retriangulation_passes"] == 0 and kept.info["untangled_vertices"] == 0
    resolved = sdflow.repair(*crossing, remove_self_intersections=True)
    # Two bodies that overlap are joined by the union, not pulled apart by moving vertices.
    assert resolved.info["self_intersecting_pairs"] == 0 and resolved.info["retriangulation_passes"] >= 1
    assert resolved.info["untangled_vertices"] == 0
    assert len(sdflow.intersections(*resolved)) == 0
    assert resolved.info["faces"] == len(resolved.F) and resolved.info["vertices"] == len(resolved.V)


def test_python_default_is_the_toolboxs():
    default = inspect.signature(sdflow.repair).parameters["merge_tolerance"].default
    assert sdflow._sdflow.repair_defaults() == {"merge_tolerance": default}
