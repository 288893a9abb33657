"""`pip install --no-build-isolation .` into a fresh venv, reusing this build tree (DRAPE_CMAKE_BUILD_DIR):
the installed package imports from any folder, is the venv's (not build/python), and predicts with the model
inside it; the `drape` console script finds shipped files by name. Skips when venv or pip is missing."""
import json
import os
import pathlib
import subprocess
import sys
import time

import pytest

from conftest import BINARY, SOURCE

CHECK = r"""
import json, sys, drape
m = drape.Model.load()
scene = drape.Scene("graphs/scenes/tshirt_coarse.yaml")
print(json.dumps({"package": drape.__file__, "model": m.file, "scene": scene.file,
                  "garment": list(m.predict(m.body(bmi=30)).shape),
                  "plugins": sorted({p["file"] for p in drape.plugins()}), "path": sys.path}))
"""


def fresh_venv(where):
    python = "/usr/bin/python3" if os.path.exists("/usr/bin/python3") else sys.executable
    made = subprocess.run([python, "-m", "venv", "--system-site-packages", str(where)], capture_output=True, text=True)
    if made.returncode != 0:
        pytest.skip(f"no venv: {python} -m venv failed (apt-get install python3-venv): {made.stderr.strip()[-200:]}")
    venv_python = where / "bin" / "python"
    if subprocess.run([venv_python, "-m", "pip", "--version"], capture_output=True).returncode != 0:
        pytest.skip("the venv has no pip (apt-get install python3-pip python3-venv)")
    for module in ("setuptools", "wheel", "numpy"):
        if subprocess.run([venv_python, "-c", f"import {module}"], capture_output=True).returncode != 0:
            pytest.skip(f"the venv sees no {module} (apt-get install python3-{module})")
    return venv_python


def test_pip_install_reusing_the_build_tree(tmp_path):
    venv = tmp_path / "venv"
    python = fresh_venv(venv)
    env = {k: v for k, v in os.environ.items()
           if k not in ("PYTHONPATH", "DRAPE_PLUGIN_PATH", "DRAPE_MODEL", "DRAPE_DATA_DIR", "PYTHONDONTWRITEBYTECODE")}
    start = time.monotonic()
    pip = subprocess.run([python, "-m", "pip", "install", "--no-build-isolation", "--no-index", "--no-cache-dir",
                          str(SOURCE)], capture_output=True, text=True, cwd=tmp_path,
                         env={**env, "DRAPE_CMAKE_BUILD_DIR": str(BINARY)})
    assert pip.returncode == 0, pip.stdout[-3000:] + pip.stderr[-3000:]
    print(f"pip install: {time.monotonic() - start:.1f} s")

    work = tmp_path / "elsewhere"
    work.mkdir()
    out = subprocess.run([python, "-c", CHECK], capture_output=True, text=True, cwd=work, env=env)
    assert out.returncode == 0, out.stderr
    r = json.loads(out.stdout.splitlines()[-1])
    site = pathlib.Path(r["package"]).resolve().parent.parent
    assert site.is_relative_to(venv.resolve()) and site.name == "site-packages", r["package"]
    assert not pathlib.Path(r["package"]).resolve().is_relative_to(BINARY.resolve())
    inside = site / "drape" / "share" / "drape"
    assert pathlib.Path(r["model"]).resolve() == inside / "models" / "tshirt-coarse-human.h5"
    assert pathlib.Path(r["scene"]).resolve() == inside / "graphs" / "scenes" / "tshirt_coarse.yaml"
    assert r["garment"] == [991, 3]
    assert r["plugins"] and all(pathlib.Path(f).resolve().is_relative_to(site / "drape" / "lib") for f in r["plugins"])

    # The drape program inside the package, by the console script.
    info = subprocess.run([venv / "bin" / "drape", "model", "info", "models/tshirt-coarse.h5"], capture_output=True,
                          text=True, cwd=work, env=env)
    assert info.returncode == 0, info.stderr
    assert pathlib.Path(info.stdout.splitlines()[0]).resolve() == inside / "models" / "tshirt-coarse.h5"
