"""Files, validation and statistics: round trips, finding codes, `stats` equal to `stats --json`."""

import base64
import json
import os
import xml.etree.ElementTree as ElementTree

import numpy as np
import pytest

import sdflow


@pytest.mark.parametrize("extension,binary", [(".off", False), (".obj", False), (".ply", False), (".ply", True)])
def test_round_trip_is_exact(torus, tmp_path, extension, binary):
    V, F = torus
    path = tmp_path / f"mesh{extension}"
    sdflow.write(path, V, F, binary=binary)
    V2, F2 = sdflow.read(path)
    np.testing.assert_array_equal(V2, V)
    np.testing.assert_array_equal(F2, F)


def test_binary_stl_rounds_to_single_precision(torus, tmp_path):
    V, F = torus
    sdflow.write(tmp_path / "mesh.stl", V, F, binary=True)
    V2, F2 = sdflow.read(tmp_path / "mesh.stl")
    assert len(V2) == len(V) and len(F2) == len(F)
    np.testing.assert_allclose(np.sort(V2, axis=0), np.sort(V.astype(np.float32).astype(np.float64), axis=0))


def test_read_matches_the_files_written_by_the_command_line(cli, meshes, tmp_path):
    out = tmp_path / "torus.off"
    cli("remesh", meshes["torus"], "-o", out, "--edge-length", 0.4, "--iterations", 1)
    V, F = sdflow.read(out)
    with open(out) as f:
        lines = [line for line in f.read().splitlines() if line and not line.startswith("#")]
    n, m, _ = map(int, lines[1].split())
    np.testing.assert_array_equal(V, np.array([[float(x) for x in line.split()] for line in lines[2:2 + n]]))
    np.testing.assert_array_equal(F, np.array([[int(x) for x in line.split()[1:]] for line in lines[2 + n:2 + n + m]]))


def test_vtp_carries_vertex_data(torus, tmp_path):
    V, F = torus
    H = sdflow.mean_curvature(V, F)
    N = sdflow.normals(V, F)
    sdflow.write(tmp_path / "s.vtp", V, F, H=H, N=N)
    # Well-formed XML; each array base64 in the appended data: a UInt64 byte count, then doubles.
    root = ElementTree.parse(tmp_path / "s.vtp").getroot()
    arrays = {a.get("Name"): a for a in root.iter("DataArray") if a.get("Name")}
    assert arrays["H"].get("NumberOfComponents") == "1" and arrays["N"].get("NumberOfComponents") == "3"
    appended = root.find("AppendedData").text.strip()[1:]

    def values(name):
        offset = int(arrays[name].get("offset"))
        head = base64.b64decode(appended[offset:offset + 12])
        count = int(np.frombuffer(head[:8], "<u8")[0])
        data = base64.b64decode(appended[offset:offset + 4 * ((8 + count + 2) // 3)])
        return np.frombuffer(data[8:8 + count], "<f8")

    np.testing.assert_array_equal(values("H"), H)
    np.testing.assert_array_equal(values("N").reshape(-1, 3), N)
    np.testing.assert_array_equal(values("Points").reshape(-1, 3), V)
    back = sdflow.read(tmp_path / "s.vtp")
    np.testing.assert_array_equal(back.V, V)


def test_ply_carries_vertex_data_as_quality_and_normals(torus, tmp_path):
    V, F = torus
    H = sdflow.mean_curvature(V, F)
    N = sdflow.normals(V, F)
    sdflow.write(tmp_path / "s.ply", V, F, H=H, N=N)
    with open(tmp_path / "s.ply") as f:
        header = f.read().split("end_header")[0]
        f.seek(0)
        lines = f.read().splitlines()
    assert "property double quality" in header and "property double nx" in header
    first = lines.index("end_header") + 1
    rows = np.array([[float(x) for x in line.split()] for line in lines[first:first + len(V)]])
    np.testing.assert_array_equal(rows[:, 3], H)
    np.testing.assert_array_equal(rows[:, 4:7], N)


def test_vertex_data_needs_ply_or_vtp(torus, tmp_path):
    V, F = torus
    with pytest.raises(sdflow.InvalidParameter, match="needs a .ply or .vtp file"):
        sdflow.write(tmp_path / "s.off", V, F, H=np.zeros(len(V)))


def test_read_reports_orientation_flip(torus, tmp_path):
    V, F = torus
    sdflow.write(tmp_path / "inward.off", V, F[:, ::-1])
    result = sdflow.read(tmp_path / "inward.off")
    assert "orientation-flipped" in [f.code for f in result.info["findings"]]
    np.testing.assert_array_equal(canonical_rows(result.F), canonical_rows(F))


def canonical_rows(F):
    """Each triangle rotated to start at its smallest index (same orientation)."""
    return np.array([np.roll(row, -int(np.argmin(row))) for row in F])


def tetrahedron():
    V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    return V, F


def test_validate_returns_codes_without_raising():
    V, F = tetrahedron()
    assert [f.severity for f in sdflow.validate(V, F)] in ([], ["info"] * len(sdflow.validate(V, F)))
    bad = {
        "face-index-out-of-range": (V, np.vstack([F, [0, 1, 7]])),
        "non-finite-coordinate": (np.vstack([V[:3], [np.nan, 0, 1]]), F),
        "face-repeated-index": (V, np.vstack([F, [1, 1, 2]])),
        "empty-mesh": (np.zeros((0, 3)), np.zeros((0, 3), int)),
    }
    for code, (v, f) in bad.items():
        findings = sdflow.validate(v, f)
        assert code in [x.code for x in findings if x.severity == "error"], (code, findings)


def test_validate_a_file_gives_the_command_lines_codes(cli, tmp_path):
    path = os.path.join(os.environ.get("SDFLOW_SOURCE_DIR", ""), "tests", "data", "bad.off")
    if not os.path.exists(path):
        pytest.skip("tests/data/bad.off not found")
    findings = sdflow.validate(path)
    stderr = cli("stats", path, check=False).stderr
    assert findings and all(f.code for f in findings)
    for f in findings:
        if f.severity == "error":
            assert f.message in stderr


def test_invalid_mesh_raises_with_findings():
    V, F = tetrahedron()
    with pytest.raises(sdflow.InvalidMesh) as e:
        sdflow.normals(V, np.vstack([F, [0, 1, 9]]))
    assert isinstance(e.value, ValueError) and e.value.exit_code == 2
    assert "face-index-out-of-range" in [f.code for f in e.value.findings]


def test_stats_equals_stats_json(cli_json, meshes):
    for name in ("torus", "dumbbell"):
        expected = cli_json("stats", meshes[name], "--json")
        assert sdflow.stats(meshes[name]) == expected
        from_arrays = sdflow.stats(*sdflow.read(meshes[name]))
        del expected["file"]
        assert from_arrays == expected


def test_unreadable_file_raises_io_error_with_the_command_lines_message(cli, tmp_path):
    path = tmp_path / "broken.off"
    path.write_text("OFF\n3 1 0\n0 0 0\n1 0 0\n")
    with pytest.raises(sdflow.IoError) as e:
        sdflow.read(path)
    assert isinstance(e.value, ValueError) and isinstance(e.value, OSError)
    assert f"sdflow: error: {e.value}" in cli("stats", path, check=False).stderr
