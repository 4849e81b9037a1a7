"""Operators: equal to the C++ toolbox's bit for bit (python/tests/operators_reference.cpp), exact
identities, no copies where promised (strides, base objects, shared memory), no leaks."""

import gc
import subprocess

import numpy as np
import pytest
import scipy.sparse

import sdflow


def reference(program, path):
    out = subprocess.run([program, path], capture_output=True, text=True, check=True).stdout
    values = {}
    for line in out.splitlines():
        name, count, *numbers = line.split()
        values[name] = np.array([float.fromhex(x) for x in numbers])
        assert len(values[name]) == int(count)
    return values


@pytest.mark.parametrize("name", ["torus", "dumbbell", "ellipsoid"])
def test_operators_equal_the_toolbox_bit_for_bit(operators_reference, meshes, name):
    ref = reference(operators_reference, meshes[name])
    V, F = sdflow.read(meshes[name])
    np.testing.assert_array_equal(sdflow.normals(V, F).ravel(), ref["normals"])
    for curvature in ("cotangent", "normal_integral", "normal_integral_angle_sum"):
        np.testing.assert_array_equal(sdflow.mean_curvature(V, F, curvature=curvature), ref[f"H_{curvature}"])
    np.testing.assert_array_equal(sdflow.mean_curvature(V, F, mass="volume_gradient"),
                                  ref["H_cotangent_volume_gradient"])
    np.testing.assert_array_equal(sdflow.mean_curvature(V, F, curvature="normal_integral"), ref["H_eq9_free_function"])
    np.testing.assert_array_equal(sdflow.vertex_areas(V, F), ref["areas_voronoi"])
    np.testing.assert_array_equal(sdflow.vertex_areas(V, F, mass="volume_gradient"), ref["areas_volume_gradient"])
    np.testing.assert_array_equal(sdflow.cotangent_laplacian(V, F).data, ref["laplacian_values"])
    H9 = sdflow.mean_curvature(V, F, curvature="normal_integral")
    d = sdflow.curvature_deviation(H9, sdflow.vertex_areas(V, F))
    assert [sdflow.area(V, F), sdflow.volume(V, F), d.mean, d.deviation, sdflow.mean_edge_length(V, F)] == \
        list(ref["area_volume_mean_deviation_edge"])


def test_the_flow_uses_the_same_operators(torus):
    V, F = torus
    flow = sdflow.Flow(V, F)
    np.testing.assert_array_equal(flow.N, sdflow.normals(V, F))
    np.testing.assert_array_equal(flow.H, sdflow.mean_curvature(V, F))
    np.testing.assert_array_equal(flow.M, sdflow.vertex_areas(V, F))
    assert abs(flow.L - sdflow.cotangent_laplacian(V, F)).max() == 0


def test_exact_identities(torus):
    V, F = torus
    L = sdflow.cotangent_laplacian(V, F)
    assert isinstance(L, scipy.sparse.csc_matrix) and L.shape == (len(V), len(V))
    assert abs(L @ np.ones(len(V))).max() < 1e-12
    assert abs(L - L.T).max() == 0
    assert np.all(L.diagonal() <= 0)
    A = sdflow.vertex_areas(V, F)
    assert A.sum() == pytest.approx(sdflow.area(V, F), rel=1e-12)
    M = sdflow.mass_matrix(V, F)
    np.testing.assert_array_equal(M.diagonal(), A)
    D = sdflow.laplace_beltrami(V, F)
    assert abs(D - scipy.sparse.diags(1 / A) @ L).max() < 1e-9


def test_sphere_has_H_minus_one_over_R():
    V, F = sdflow.shape("sphere", radius=2, vertices=2000)
    H = sdflow.mean_curvature(V, F)
    assert np.median(H) == pytest.approx(-0.5, rel=1e-3)
    N = sdflow.normals(V, F)
    np.testing.assert_allclose(np.einsum("ij,ij->i", N, V / np.linalg.norm(V, axis=1)[:, None]), 1, atol=1e-3)
    assert sdflow.volume(V, F) == pytest.approx(4 / 3 * np.pi * 8, rel=1e-2)


def test_results_are_not_copied(torus):
    V, F = torus
    for array in (V, F, sdflow.normals(V, F), sdflow.mean_curvature(V, F), sdflow.vertex_areas(V, F)):
        assert not array.flags.owndata, "the array owns a copy"
        assert type(array.base).__name__ == "PyCapsule", "the array does not view the toolbox's result"
        assert array.flags.c_contiguous and array.flags.writeable
    assert V.dtype == np.float64 and V.strides == (24, 8)
    assert F.dtype == np.int32 and F.strides == (12, 4)
    L = sdflow.cotangent_laplacian(V, F)
    roots = [root_base(a) for a in (L.data, L.indices, L.indptr)]
    assert all(type(r).__name__ == "PyCapsule" for r in roots), roots
    assert roots[0] is roots[1] is roots[2], "data, indices and pointers share the toolbox's matrix"


def root_base(array):
    """The object at the end of an array's chain of bases."""
    while isinstance(array, np.ndarray) and array.base is not None:
        array = array.base
    return array


def test_inputs_are_read_in_place(torus):
    V, F = torus
    V = np.ascontiguousarray(V)
    assert sdflow._sdflow._vertex_address(V) == V.__array_interface__["data"][0]
    fortran = np.asfortranarray(V)
    assert sdflow._sdflow._vertex_address(fortran) != fortran.__array_interface__["data"][0]
    np.testing.assert_array_equal(sdflow.normals(fortran, F), sdflow.normals(V, F))
    view = np.hstack([V, V])[:, :3]  # strided: converted once, same result
    np.testing.assert_array_equal(sdflow.normals(view, F), sdflow.normals(V, F))


@pytest.mark.parametrize("dtype", [np.int32, np.int64, np.uint32, np.intp])
def test_face_dtypes(torus, dtype):
    V, F = torus
    np.testing.assert_array_equal(sdflow.mean_curvature(V, F.astype(dtype)), sdflow.mean_curvature(V, F))


def test_bad_arrays_raise_value_errors(torus):
    V, F = torus
    with pytest.raises(ValueError, match=r"V must have shape \(n, 3\)"):
        sdflow.normals(V[:, :2], F)
    with pytest.raises(ValueError, match="F must hold integer vertex indices"):
        sdflow.normals(V, F.astype(float))
    with pytest.raises(ValueError, match=r"curvature must be"):
        sdflow.mean_curvature(V, F, curvature="gauss")


def resident_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * 4096


def test_results_are_freed(torus):
    V, F = torus
    V, F = sdflow.remesh(V, F, edge_length=0.15, iterations=1)  # ~9k vertices
    for _ in range(5):
        sdflow.normals(V, F), sdflow.cotangent_laplacian(V, F)
    gc.collect()
    before = resident_bytes()
    for _ in range(60):
        N = sdflow.normals(V, F)
        L = sdflow.cotangent_laplacian(V, F)
        del N, L
    gc.collect()
    grown = resident_bytes() - before
    # 60 normals (~0.2 MB each) and Laplacians (~1.2 MB each) kept would be ~85 MB.
    assert grown < 20e6, f"{grown / 1e6:.1f} MB more after 60 rounds"
