"""Shapes and the re-triangulation stages: the same meshes as the command line's verbs, bit for bit."""

import numpy as np
import pytest

import sdflow


def test_shape_equals_sdflow_shape(cli, tmp_path):
    cli("shape", "torus", "--major", 3, "--minor", 1, "--vertices", 1200, "-o", tmp_path / "t.ply")
    V, F = sdflow.shape("torus", major=3, minor=1, vertices=1200)
    V2, F2 = sdflow.read(tmp_path / "t.ply")
    np.testing.assert_array_equal(V, V2)
    np.testing.assert_array_equal(F, F2)


def test_formula_shape(cli, tmp_path):
    box = (-2, -2, -2, 2, 2, 2)
    V, F = sdflow.shape(expression="x^2 + y^2 + z^2 - 1", box=box, edge_length=0.2)
    cli("shape", "--expr", "x^2 + y^2 + z^2 - 1", "--box", ",".join(map(str, box)), "--edge-length", 0.2,
        "-o", tmp_path / "s.ply")
    np.testing.assert_array_equal(V, sdflow.read(tmp_path / "s.ply").V)
    assert sdflow.volume(V, F) == pytest.approx(4 / 3 * np.pi, rel=0.02)


def test_shape_catalogue_and_errors():
    catalogue = sdflow.shapes()
    assert set(catalogue) >= {"sphere", "ellipsoid", "torus", "dumbbell", "sintering", "spheres-on-plane"}
    assert catalogue["torus"]["parameters"]["major"][0] == 6
    with pytest.raises(sdflow.InvalidParameter):
        sdflow.shape("teapot", vertices=100)
    with pytest.raises(sdflow.InvalidParameter, match="not both"):
        sdflow.shape("torus", vertices=100, edge_length=0.1)
    with pytest.raises(sdflow.InvalidParameter):
        sdflow.shape("torus", vertices=10 ** 9)  # the plausibility limit


def test_packing_is_in_the_catalogue_and_meshes_its_ring(cli, tmp_path):
    assert "min-distance" in sdflow.shapes()["packing"]["parameters"]
    # Four spheres in a ring: genus 1, as `sdflow shape packing` makes it.
    ring = sdflow.shape("packing", nx=2, ny=2, nz=1, edge_length=0.25)
    V, F = ring.V, ring.F
    cli("shape", "packing", "--nx", 2, "--ny", 2, "--nz", 1, "--edge-length", 0.25, "-o", tmp_path / "p.ply")
    np.testing.assert_array_equal(V, sdflow.read(tmp_path / "p.ply").V)
    np.testing.assert_array_equal(F, sdflow.read(tmp_path / "p.ply").F)
    with pytest.raises(sdflow.InvalidParameter):
        sdflow.shape("packing", count=10, spacing=1.8, min_distance=1.0, edge_length=0.2)


def test_retriangulate_equals_sdflow_retriangulate(cli, cli_json, meshes, tmp_path):
    report = cli_json("retriangulate", meshes["dumbbell"], "-o", tmp_path / "r.ply", "--edge-length", 0.4, "--json")
    V, F = sdflow.read(meshes["dumbbell"])
    result = sdflow.retriangulate(V, F, edge_length=0.4)
    V2, F2 = sdflow.read(tmp_path / "r.ply")
    np.testing.assert_array_equal(result.V, V2)
    np.testing.assert_array_equal(result.F, F2)
    for key, value in report.items():
        if key not in ("input", "output", "seconds"):
            assert result.info[key] == value, key


def test_remesh_equals_sdflow_remesh(cli, meshes, tmp_path):
    cli("remesh", meshes["torus"], "-o", tmp_path / "r.ply", "--edge-length", 0.3, "--iterations", 2)
    V, F = sdflow.remesh(*sdflow.read(meshes["torus"]), edge_length=0.3, iterations=2)
    np.testing.assert_array_equal(V, sdflow.read(tmp_path / "r.ply").V)


def test_remesh_keep_boundary_keeps_the_rim_as_sdflow_remesh_does(cli, tmp_path):
    # The upper half of an ellipsoid: a surface with one boundary loop.
    V, F = sdflow.shape(name="ellipsoid", vertices=800)
    keep = (V[F][:, :, 2].mean(axis=1) > 0)
    used, F_half = np.unique(F[keep], return_inverse=True)
    V_half, F_half = V[used], F_half.reshape(-1, 3).astype(F.dtype)
    sdflow.write(tmp_path / "half.ply", V_half, F_half, binary=True)
    # At about the rim's own edge length (0.53); the remeshing alone leaves 3 edges shorter than
    # half the target beside the rim here, the settling none.
    cli("remesh", tmp_path / "half.ply", "-o", tmp_path / "r.ply", "--edge-length", 0.55, "--iterations", 5,
        "--keep-boundary")
    R, G = sdflow.remesh(V_half, F_half, edge_length=0.55, iterations=5, keep_boundary=True)
    np.testing.assert_array_equal(R, sdflow.read(tmp_path / "r.ply").V)
    np.testing.assert_array_equal(G, sdflow.read(tmp_path / "r.ply").F)
    assert rim_points(R, G) == rim_points(V_half, F_half)
    edges = np.sort(np.concatenate([G[:, [0, 1]], G[:, [1, 2]], G[:, [2, 0]]]), axis=1)
    on_rim = np.isin(edges, rim_vertices(G))
    beside_rim = on_rim[:, 0] != on_rim[:, 1]
    lengths = np.linalg.norm(R[edges[:, 0]] - R[edges[:, 1]], axis=1)
    assert not np.any(beside_rim & (lengths < 0.5 * 0.55))


def rim_vertices(F):
    """The vertices on edges that only one face has."""
    edges = np.sort(np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]), axis=1)
    unique, counts = np.unique(edges, axis=0, return_counts=True)
    return np.unique(unique[counts == 1])


def rim_points(V, F):
    return {tuple(p) for p in V[rim_vertices(F)]}


def test_intersections_union_and_the_pipeline_on_overlapping_spheres(cli_json, tmp_path):
    V, F = sdflow.shape("sphere", vertices=600)
    V2 = V + [1.0, 0, 0]
    sdflow.write(tmp_path / "a.ply", V, F, binary=True)
    sdflow.write(tmp_path / "b.ply", V2, F, binary=True)
    pairs = sdflow.intersections(V, F, V2, F)
    expected = cli_json("intersections", tmp_path / "a.ply", tmp_path / "b.ply", "--json")
    assert pairs.shape[1] == 2 and pairs.tolist() == expected["pairs"]
    both = (np.vstack([V, V2]), np.vstack([F, F + len(V)]))
    assert len(sdflow.intersections(*both)) == len(pairs)
    united = sdflow.union(V, F, V2, F)
    assert sdflow.stats(*united, tetgen=False)["component_count"] == 1
    assert sdflow.volume(*united) > sdflow.volume(V, F)
    merged = sdflow.retriangulate(*both)
    assert merged.info["merged_components"] == 1 and merged.info["components_after"] == 1
    kept = sdflow.remove_intersections(*both)
    assert len(kept.F) < len(both[1]) and len(kept.info["removed_faces"]) > 0


def test_stages_on_points_and_holes():
    V, F = sdflow.shape("sphere", vertices=800)
    points, normals, source, removed = sdflow.point_normals(V)
    assert len(points) + len(removed) == len(V)
    assert np.all(np.einsum("ij,ij->i", normals, points) > 0), "outward"
    rebuilt = sdflow.reconstruct(points, normals)
    assert sdflow.stats(*rebuilt, tetgen=False)["boundary_loops"] == 0
    open_ = sdflow.components(V, F[V[F].mean(axis=1)[:, 2] < 0.9])
    assert sdflow.stats(*open_, tetgen=False)["boundary_loops"] == 1
    filled = sdflow.fill_holes(*open_)
    assert filled.info["loops"][0]["outcome"] == "filled"
    assert sdflow.stats(*filled, tetgen=False)["boundary_loops"] == 0
    parts = sdflow.components(np.vstack([V, V + 5]), np.vstack([F, F + len(V)]), split=True)
    assert len(parts) == 2


def test_python_defaults_are_the_toolboxs():
    import inspect
    defaults = sdflow._sdflow.defaults()
    for name, values in defaults.items():
        signature = inspect.signature(getattr(sdflow, name))
        for key, value in values.items():
            assert signature.parameters[key].default == pytest.approx(value), (name, key)
    shape = inspect.signature(sdflow.shape)
    for key, value in sdflow._sdflow.shape_defaults().items():
        assert shape.parameters[key].default == value, key
