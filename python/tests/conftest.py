"""Fixtures of the Python tests: the built command line (SDFLOW_CLI, set by ctest), the C++
operators program (SDFLOW_OPERATORS_REFERENCE) and small meshes written to files both read."""

import json
import os
import subprocess

import numpy as np
import pytest

import sdflow

SOURCE_DIR = os.environ.get("SDFLOW_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))


def _program(variable):
    path = os.environ.get(variable, "")
    if not path or not os.path.exists(path):
        pytest.skip(f"{variable} is not set to a built program (run the tests through ctest)")
    return path


@pytest.fixture(scope="session")
def cli():
    """Run the `sdflow` command line: cli(args...) → CompletedProcess (text)."""
    path = _program("SDFLOW_CLI")

    def run(*args, check=True):
        result = subprocess.run([path, *map(str, args)], capture_output=True, text=True)
        if check and result.returncode != 0:
            raise AssertionError(f"sdflow {' '.join(map(str, args))}: exit {result.returncode}\n{result.stderr}")
        return result
    return run


@pytest.fixture(scope="session")
def cli_json(cli):
    return lambda *args: json.loads(cli(*args).stdout)


@pytest.fixture(scope="session")
def operators_reference():
    return _program("SDFLOW_OPERATORS_REFERENCE")


@pytest.fixture(scope="session")
def meshes(tmp_path_factory):
    """Small meshes as files (binary PLY, doubles): a torus and a dumbbell that pinches off."""
    folder = tmp_path_factory.mktemp("meshes")
    files = {}
    for name, args in {"torus": dict(name="torus", major=3, minor=1.5, vertices=1500),
                       "dumbbell": dict(name="dumbbell", radius=3, separation=9, edge_length=0.5),
                       "ellipsoid": dict(name="ellipsoid", vertices=800)}.items():
        V, F = sdflow.shape(**args)
        files[name] = str(folder / f"{name}.ply")
        sdflow.write(files[name], V, F, binary=True)
    return files


@pytest.fixture(scope="session")
def torus(meshes):
    return sdflow.read(meshes["torus"])


def read_metrics(path):
    with open(path) as f:
        return f.read().splitlines()


@pytest.fixture
def metrics_lines():
    return read_metrics
