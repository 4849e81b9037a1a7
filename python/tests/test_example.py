"""The example script runs (a coarse torus, through its seal) and draws its figure."""

import os
import subprocess
import sys

EXAMPLE = os.path.join(os.path.dirname(__file__), "..", "examples", "torus_seal.py")


def test_torus_seal_example_runs(tmp_path):
    figure = tmp_path / "seal.png"
    result = subprocess.run([sys.executable, EXAMPLE, "--vertices", "1500", "--out", str(figure)],
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert "the hole sealed at t = " in result.stdout
    assert figure.stat().st_size > 10_000
