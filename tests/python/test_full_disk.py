"""Model.save on a disk that fills up raises drape.Error: HDF5 cannot close a file whose last flush fails, and
closing it again took the interpreter down with SIGSEGV (an outside check). The disk is filled by a preloaded
library after a given number of bytes (tests/fixtures/preload/full_disk.c), in a Python process of its own."""
import os
import subprocess
import sys

import pytest

from conftest import BINARY, SOURCE

PRELOAD = BINARY / "test-fixtures" / "preload" / "libfull_disk.so"

SCRIPT = """
import sys, warnings, drape
warnings.simplefilter("ignore")
model = drape.Model.load(sys.argv[1])
try:
    model.save(sys.argv[2])
    print("saved")
except drape.Error as e:
    print("refused:", e)
"""


@pytest.mark.parametrize("room", [0, 50000, 600000])
def test_a_save_on_a_full_disk_raises_and_leaves_nothing(tmp_path, room):
    if not PRELOAD.exists():
        pytest.skip(f"the full-disk fixture {PRELOAD} is not built")
    env = dict(os.environ, LD_PRELOAD=str(PRELOAD), DRAPE_TEST_DISK_BYTES=str(room))
    out = tmp_path / "copy.h5"
    p = subprocess.run([sys.executable, "-c", SCRIPT, str(SOURCE / "models" / "tshirt-coarse.h5"), str(out)],
                       env=env, capture_output=True, text=True, timeout=120, cwd=tmp_path)
    assert p.returncode == 0, (p.returncode, p.stdout, p.stderr)
    assert "refused:" in p.stdout and "No space left on device" in p.stdout, p.stdout
    assert not out.exists()
    assert [f.name for f in tmp_path.iterdir()] == [], "a temporary was left behind"
