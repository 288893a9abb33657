"""Bad input to every Python entry point and loader ends in a Python exception with a message, never a crash
or a hang (issue 58): NaN, inf, 1e308, wrong shapes and dtypes, truncated, bit-flipped and unsealed files.
A crash would end the interpreter and fail this file; each call also runs under a 30 s alarm."""
import signal

import numpy as np
import pytest

import drape
from conftest import COARSE, SOURCE

SHIPPED = SOURCE / "models" / "tshirt-coarse.h5"
DATASET = sorted((SOURCE / "datasets" / "bodyspace2000-friction").glob("shard-*.h5"))[0]


def refused(call, *args, **kwargs):
    """Runs call(*args) under a 30 s alarm; returns the exception it raised (None when it returned)."""
    def on_alarm(signum, frame):
        raise TimeoutError(f"{call} did not answer within 30 s")
    previous = signal.signal(signal.SIGALRM, on_alarm)
    signal.alarm(30)
    try:
        call(*args, **kwargs)
        return None
    except TimeoutError:
        raise
    except Exception as e:  # noqa: BLE001  (any Python exception is an answer; a crash is not)
        assert str(e), f"{call} raised {type(e).__name__} without a message"
        return e
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, previous)


def bad_arrays(rows):
    good = np.zeros((rows, 3))
    out = []
    for value in (np.nan, np.inf, -np.inf, 1e308):
        a = good.copy()
        a[rows // 2, 1] = value
        out.append(a)
    out += [good[:-1], good[:, :2], good.astype(np.int64), good.astype(object), np.zeros((0, 3)), np.zeros(rows),
            "body", None, [[0.0, 0.0]], np.zeros((2, rows, 3, 1))]
    return out


@pytest.fixture(scope="module")
def model():
    return drape.Model.load(str(SHIPPED))


def test_model_predict_and_body_refuse_bad_input(model):
    for bad in bad_arrays(model.body_vertex_count):
        e = refused(model.predict, bad)
        assert e is not None, f"predict accepted {bad!r:.80}"
    for bmi in (np.nan, np.inf, -1.0, 1e308, "x", None):
        assert refused(model.body, bmi=bmi) is not None, bmi


def test_energies_refuse_bad_positions():
    scene = drape.Scene(str(COARSE))
    energies = scene.energies(np.array(scene.mean_body))
    n = len(scene.garment_vertices)
    for name, e in energies.items():
        for bad in bad_arrays(n):
            for call in (e.value, e.gradient, e.hessian):
                answer = refused(call, bad)
                # 1e308 is finite: an energy may evaluate it (to inf) or refuse it, but must answer.
                finite = isinstance(bad, np.ndarray) and bad.dtype.kind == "f" and bad.shape == (n, 3) and np.isfinite(bad).all()
                if not finite:
                    assert answer is not None, f"{name}.{call.__name__} accepted {bad!r:.80}"


def test_simulate_refuses_bad_bodies():
    scene = drape.Scene(str(COARSE))
    for bad in bad_arrays(len(scene.mean_body)):
        if bad is None:
            continue  # the scene's own body: a whole simulation, not bad input
        assert refused(scene.simulate, bad) is not None, f"simulate accepted {bad!r:.80}"


def damaged_copies(source, tmp_path):
    data = source.read_bytes()
    files = {}
    for name, content in {
        "empty": b"",
        "text": b"not a drape file\n",
        "truncated_half": data[: len(data) // 2],
        "truncated_head": data[:600],
    }.items():
        files[name] = tmp_path / f"{name}{source.suffix}"
        files[name].write_bytes(content)
    for k, at in enumerate((520, 700, len(data) // 3, len(data) - 100)):  # past the 512-byte seal block
        flipped = bytearray(data)
        flipped[at] ^= 0x40
        files[f"flipped_{k}"] = tmp_path / f"flipped_{k}{source.suffix}"
        files[f"flipped_{k}"].write_bytes(bytes(flipped))
    # Unsealed: the checksum block zeroed, as a killed writer or an h5py edit leaves it (h5_seal.hpp).
    unsealed = bytearray(data)
    unsealed[:512] = bytes(512)
    files["unsealed"] = tmp_path / f"unsealed{source.suffix}"
    files["unsealed"].write_bytes(bytes(unsealed))
    files["missing"] = tmp_path / f"missing{source.suffix}"
    files["folder"] = tmp_path
    return files


def test_loaders_refuse_damaged_files(tmp_path):
    (tmp_path / "m").mkdir()
    (tmp_path / "d").mkdir()
    for name, path in damaged_copies(SHIPPED, tmp_path / "m").items():
        answer = refused(drape.Model.load, str(path))
        assert answer is not None or name == "unsealed", f"Model.load accepted the {name} model file"
    for name, path in damaged_copies(DATASET, tmp_path / "d").items():
        def read_all(p=path):
            d = drape.Dataset(str(p))
            len(d)
        answer = refused(read_all)
        assert answer is not None or name == "unsealed", f"Dataset accepted the {name} dataset"
    bad_scene = tmp_path / "s.yaml"
    for text in ("effects: [", "effects: {gravity: {g: nan}}", "base: s.yaml", "\x00\x01", "solver: {time_step: 1e308}"):
        bad_scene.write_text(text)
        assert refused(drape.Scene, str(bad_scene)) is not None or "time_step" in text, text


def test_a_model_whose_weight_is_nan_is_refused_at_load_naming_the_weight(tmp_path):
    """An h5py edit (the file unsealed) that leaves a NaN weight: refused at load, naming the file and the weight,
    where predict failed at the push-out with "the garment has a non-finite vertex"."""
    import h5py
    edited = tmp_path / "nan.h5"
    edited.write_bytes(SHIPPED.read_bytes())
    with h5py.File(edited, "r+") as f:
        names = []
        f["weights"].visititems(lambda n, o: names.append(n) if isinstance(o, h5py.Dataset) else None)
        name = sorted(names)[0]
        w = f["weights"][name][...]
        w.flat[0] = np.nan
        f["weights"][name][...] = w
    raw = bytearray(edited.read_bytes())
    raw[:512] = bytes(512)  # unsealed, as h5py leaves a file it wrote
    edited.write_bytes(bytes(raw))
    e = refused(drape.Model.load, str(edited))
    assert isinstance(e, ValueError) and f"weight {name} holds a value that is not a finite number" in str(e)


def test_module_functions_and_the_torch_bridge_refuse_bad_input():
    for bmi in (np.nan, np.inf, -5.0, 1e308):
        assert refused(drape.body, bmi=bmi) is not None, bmi
    for resolution in ("huge", -1, np.nan):
        assert refused(drape.assets, resolution=resolution) is not None, resolution
    torch = pytest.importorskip("torch", reason="PyTorch is not installed (Debian: python3-torch)")
    import drape.torch_bridge as dt
    physics = dt.SceneEnergy(str(COARSE))
    x = torch.tensor(np.array(physics.scene.garment_vertices), dtype=torch.float64)
    x[5, 2] = float("nan")
    e = refused(physics, x)
    assert isinstance(e, ValueError) and "non-finite coordinate" in str(e)


def test_core_warnings_are_python_warnings(tmp_path):
    # drape::warn's channel (drape/warnings.hpp) becomes drape.DrapeWarning, a UserWarning that filters see.
    import drape
    assert issubclass(drape.DrapeWarning, UserWarning)
    # (A folder holding a file named as a plugin that is none: refused with a warning, as --plugin-path does;
    # a path that does not exist is a ConfigError since the fifty-third session, test_arguments.py.)
    folder = tmp_path / "plugins"
    folder.mkdir()
    (folder / "libdrape_plugin_fake.so").write_bytes(b"not a library")
    with pytest.warns(drape.DrapeWarning, match="refused plugin"):
        drape.load_plugins(str(folder))
    (folder / "libdrape_plugin_fake2.so").write_bytes(b"not a library either")
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error", drape.DrapeWarning)
        with pytest.raises(drape.DrapeWarning):
            drape.load_plugins(str(folder))
