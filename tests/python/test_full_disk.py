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


def test_save_writes_over_a_model_only_and_not_while_another_job_writes_the_path(tmp_path):
    import fcntl
    import drape
    model = drape.Model.load(str(SOURCE / "models" / "tshirt-coarse.h5"))
    dataset = tmp_path / "data.h5"
    dataset.write_bytes(b"not a model")
    with pytest.raises(drape.ConfigError, match="is written over a model only"):
        model.save(str(dataset))
    assert dataset.read_bytes() == b"not a model"
    # A job holding the output's lock (a drape train writing it, which wrote over this save at its next epoch).
    busy = tmp_path / "busy.h5"
    with open(str(busy) + ".lock", "w") as lock:
        lock.write("pid 1, drape train")
        lock.flush()
        fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
        with pytest.raises(drape.ConfigError, match="drape train"):
            model.save(str(busy))
    assert not busy.exists()
    model.save(str(busy))  # the lock let go: saved, over nothing
    assert drape.Model.load(str(busy)).garment_vertex_count == model.garment_vertex_count
