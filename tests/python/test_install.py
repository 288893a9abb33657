"""cmake --install puts the package under the prefix's site-packages, and the installed module uses the
prefix's own framework library, plugins and shipped model (not the build tree's)."""
import json
import os
import pathlib
import subprocess
import sys

from conftest import BINARY

CHECK = r"""
import json, drape
m = drape.Model.load()
print(json.dumps({"package": drape.__file__, "model": m.file, "garment": list(m.predict(m.body(bmi=30)).shape),
                  "plugins": sorted({p["file"] for p in drape.plugins()})}))
"""


def test_installed_package_imports_from_the_prefix(tmp_path):
    prefix = tmp_path / "prefix"
    cmake = os.environ.get("DRAPE_CMAKE_COMMAND", "cmake")
    subprocess.run([cmake, "--install", str(BINARY), "--prefix", str(prefix)], check=True, capture_output=True)
    site = [p for p in prefix.glob("lib*/python3*/*-packages") if (p / "drape").is_dir()]
    assert len(site) == 1, list(prefix.rglob("__init__.py"))
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "DRAPE_PLUGIN_PATH", "DRAPE_MODEL")}
    env["PYTHONPATH"] = str(site[0])
    out = subprocess.run([sys.executable, "-c", CHECK], check=True, capture_output=True, text=True, env=env,
                         cwd=tmp_path).stdout
    r = json.loads(out.splitlines()[-1])
    real_prefix = pathlib.Path(os.path.realpath(prefix))
    assert pathlib.Path(r["package"]).resolve().is_relative_to(real_prefix)
    assert pathlib.Path(r["model"]).resolve() == real_prefix / "share" / "drape" / "models" / "tshirt-coarse-human.h5"
    assert r["garment"] == [991, 3]
    assert r["plugins"] and all(pathlib.Path(f).resolve().is_relative_to(real_prefix) for f in r["plugins"])
