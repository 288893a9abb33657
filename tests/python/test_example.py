"""examples/python/drape_example.py runs as the docs show it and does what it says."""
import os
import re
import subprocess
import sys

import pytest

import drape
from conftest import SOURCE, read_obj

pytest.importorskip("torch", reason="the example trains with PyTorch (Debian: python3-torch)")


def test_the_example_writes_a_drape_of_lower_potential(tmp_path):
    out, body_out = tmp_path / "garment.obj", tmp_path / "body.obj"
    env = dict(os.environ, PYTHONPATH=os.path.dirname(os.path.dirname(os.path.abspath(drape.__file__))))
    p = subprocess.run([sys.executable, str(SOURCE / "examples" / "python" / "drape_example.py"), "--bmi", "30",
                        "--iterations", "8", "--out", str(out), "--body-out", str(body_out)],
                       capture_output=True, text=True, timeout=120, env=env, cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    potentials = [float(x) for x in re.findall(r"potential ([0-9.]+) J", p.stdout)]
    assert len(potentials) == 2 and potentials[1] < potentials[0], p.stdout
    garment, faces = read_obj(out)
    body, _ = read_obj(body_out)
    assert garment.shape == (991, 3) and faces.shape[1] == 3 and body.shape[1] == 3
