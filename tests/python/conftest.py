"""Shared fixtures of the drape Python tests. CTest runs each test file with PYTHONPATH at the build tree's
python/ folder and DRAPE_SOURCE_DIR / DRAPE_BINARY_DIR set (python/CMakeLists.txt)."""
import os
import pathlib
import subprocess
import sys

import pytest

SOURCE = pathlib.Path(os.environ.get("DRAPE_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
BINARY = pathlib.Path(os.environ.get("DRAPE_BINARY_DIR", SOURCE / "build"))
DRAPE = BINARY / "bin" / "drape"
COARSE = SOURCE / "graphs" / "scenes" / "tshirt_coarse.yaml"
CONTACT = SOURCE / "graphs" / "scenes" / "tshirt_coarse_contact.yaml"
REFERENCE = SOURCE / "scripts" / "reference"  # the checks written apart from drape (numpy only)

sys.path.insert(0, str(REFERENCE))
from obj_file import read_obj  # noqa: E402,F401  (an OBJ reader independent of drape's, for the tests)


# A model small enough to check weight by weight (test_torch), or to save as a model file without training
# one (test_reference_winding): tanh keeps it smooth, so central differences never straddle a ReLU kink, and
# its untrained weights predict little more than the template, the shirt of the mean body.
TINY_GRAPH = """
inputs:
  body: [body_vertices, 3]
nodes:
  shape: { type: subtract_mean_body, in: body }
  encoder: { type: cnn1d, in: shape, params: { channels: [4], kernel: 5, stride: 8, activation: tanh } }
  decoder: { type: mlp, in: encoder.global, params: { widths: [8], rows: 0, activation: tanh } }
  garment: { type: add_template, in: decoder }
outputs: { garment: garment }
"""


def run_drape(*args, expect=0):
    """Runs the drape program; returns (stdout, stderr). Fails the test on another exit code (expect: one code,
    or a tuple of the codes allowed). The timeout only keeps a hung run from stalling the suite: a BMI 45 drape of
    30 s on a quiet machine took over 120 s on one loaded with two builds and other jobs (the timeout was 120)."""
    p = subprocess.run([str(DRAPE), *map(str, args)], capture_output=True, text=True, timeout=900)
    allowed = expect if isinstance(expect, tuple) else (expect,)
    assert p.returncode in allowed, f"drape {' '.join(map(str, args))} exited {p.returncode}:\n{p.stderr}"
    return p.stdout, p.stderr


def run_script(script, *args, timeout=300):
    """Runs a script of scripts/ with this build's drape module on its path; returns the CompletedProcess."""
    import drape
    env = dict(os.environ, PYTHONPATH=os.path.dirname(os.path.dirname(os.path.abspath(drape.__file__))))
    return subprocess.run([sys.executable, str(script), *map(str, args)], capture_output=True, text=True,
                          timeout=timeout, env=env)


def penalty_scene(path, morph_steps=0):
    """A scene of seconds for the scripts' tests: the coarse T-shirt with the penalty contact (so that the body
    moves the cloth even without a morph), one settling step cut at 8 Newton iterations, Eigen's Cholesky."""
    path.write_text(f"base: {SOURCE / 'graphs' / 'scenes' / 'tshirt_coarse_penalty.yaml'}\n"
                    f"solver: {{morph_steps: {morph_steps}, settle_steps: 1, max_newton_iterations: 8, linear_solver: eigen}}\n")
    return path


@pytest.fixture(scope="session")
def drape_module():
    import drape
    return drape


@pytest.fixture
def tiny_scene(tmp_path):
    """The coarse T-shirt without body contact, settled for a few steps from the mean body, each step cut
    at 8 Newton iterations: a simulation of about a second (uncut, the steps took 85 iterations, 5 s, and
    this fixture was most of the Python tests' time). Eigen's Cholesky rather than CHOLMOD: CHOLMOD's
    rounding follows the BLAS kernels OpenBLAS picks per process (the drape program may ask for other ones
    than a Python process gets), and three unsettled Newton steps amplify that to centimetres; Eigen's is
    the same everywhere."""
    path = tmp_path / "tiny.yaml"
    path.write_text(f"base: {COARSE}\neffects: {{barrier: null}}\n"
                    "solver: {morph_steps: 0, settle_steps: 3, max_newton_iterations: 8, linear_solver: eigen}\n")
    return path
