"""drape from Python: bodies, garment assets, trained models, cloth scenes and
their energies, datasets -- NumPy arrays in and out (docs/python.md).

    import drape
    body, faces = drape.body(bmi=35, height=1.80, sex=1)
    model = drape.Model.load()                  # the shipped pretrained model
    garment = model.predict(model.body(bmi=35))  # float32 [991, 3]
    result = drape.simulate("graphs/scenes/tshirt_coarse.yaml", body)

Errors are drape.ConfigError (also a ValueError: bad input, exit code 2 of the
drape program) and drape.Error (a RuntimeError: anything else), with the
program's one-line messages. The PyTorch bridge is drape.torch_bridge.
"""
import contextlib as _contextlib
import json as _json
import operator as _operator
import os as _os
import tempfile as _tempfile

import numpy as _np

from ._drape import (  # noqa: F401  (re-exported)
    BodyModel,
    ConfigError,
    Dataset,
    DrapeWarning,
    Error,
    Model,
    __version__,
    better_blas_coretype,
    blas_corename,
    body,
    data_dirs,
    dataset_name,
    find_file,
    load_plugins,
    plugin_search_path,
    plugins,
)
from . import _drape

__all__ = [
    "Assets", "BodyModel", "ConfigError", "Dataset", "DrapeWarning", "Energy", "Error", "Model", "Scene", "assets",
    "better_blas_coretype", "blas_corename", "body",
    "data_dirs", "dataset_name", "find_file", "generate", "load_plugins", "plugin_search_path", "plugins", "simulate", "sparse",
]


def __getattr__(name):
    # drape.TorchDataset without importing PyTorch with the package (it takes seconds, and is optional).
    if name == "TorchDataset":
        from .torch_data import DrapeDataset
        return DrapeDataset
    raise AttributeError(f"module 'drape' has no attribute '{name}'")


def sparse(coo):
    """A (rows, cols, values, shape) COO tuple as a SciPy CSR matrix (duplicates summed), or the tuple itself
    when SciPy is not installed."""
    try:
        import scipy.sparse
    except ImportError:
        return coo
    rows, cols, values, shape = coo
    return scipy.sparse.coo_matrix((values, (rows, cols)), shape=shape).tocsr()


class Assets:
    """A garment template's precomputed assets: the garment dressed on the mean body, its UVs, the mean body,
    the body->garment correspondences, the 4-level hierarchy, graph Laplacians and the spectral basis.
    Arrays are read-only views of drape's cached assets."""

    def __init__(self, native):
        self._a = native

    def __getattr__(self, name):
        return getattr(self._a, name)

    @property
    def laplacians(self):
        """Random-walk graph Laplacian I - D^-1 A of each hierarchy level (SciPy sparse, or COO tuples)."""
        return [sparse(c) for c in self._a._laplacians]

    @property
    def hierarchy(self):
        levels = self._a.hierarchy
        for level in levels:
            if level["upsample"] is not None:
                level["upsample"] = sparse(level["upsample"])
        return levels

    def __repr__(self):
        d = self._a.dims
        return f"<drape.Assets garment {d['garment_vertices']} vertices, body {d['body_vertices']}, k {d['eigen_k']}>"


def assets(resolution=None, garment="tshirt", size=None, body_model="parametric", eigen_k=1000, levels=4,
           garment_params=None, body_params=None, cache_dir=None):
    """The template's assets as `drape assets` builds them (cached in HDF5 under $DRAPE_CACHE_DIR or
    ~/.cache/drape), e.g. drape.assets(resolution="coarse")."""
    gp = dict(garment_params or {})
    if resolution is not None:
        gp["resolution"] = resolution
    if size is not None:
        gp["size"] = size
    return Assets(_drape._assets(garment, gp, body_model, dict(body_params or {}), int(eigen_k), int(levels), cache_dir))


_Model_assets = Model.assets
Model.assets = property(lambda self: Assets(_Model_assets.fget(self)), doc="the model's template assets (drape.Assets)")


class Energy:
    """One effect of a scene bound to the garment and a body: value, gradient and Hessian at a garment state
    x (float [Ng, 3], metres). Physics in double precision."""

    def __init__(self, energies, name):
        self._e = energies
        self.name = name

    def value(self, x):
        """E(x) in J."""
        return self._e.value(self.name, x)

    def gradient(self, x):
        """dE/dx, float64 [Ng, 3] (N)."""
        return self._e.value_and_gradient(self.name, x)[1]

    def value_and_gradient(self, x):
        return self._e.value_and_gradient(self.name, x)

    def hessian(self, x, project_psd=False):
        """d2E/dx2 on the flattened index 3*vertex + axis, [3Ng, 3Ng]: SciPy sparse (CSR) when SciPy is
        installed, else the COO tuple (rows, cols, values, shape) with duplicates to be summed. project_psd
        projects each element block to the nearest PSD matrix, as the Newton solver does."""
        return sparse(self._e.hessian(self.name, x, bool(project_psd)))

    def max_step(self, x, dx):
        """The fraction in [0, 1] of the move x -> x + dx a line search may start from (ConfigError for a NaN or
        infinite position or step). 1 for the energies finite everywhere. For a barrier contact (barrier,
        self_contact) it is a conservative share of the first time of contact found by continuous collision
        detection: no pair comes closer than a safe share of its distance before it, so a line search from it never
        lets the surfaces cross. It is not where the energy turns infinite: the energy is still finite well beyond it,
        and the straight move past a contact may even end finite on the other side."""
        return self._e.max_step(self.name, x, dx)

    def __repr__(self):
        return f"<drape.Energy {self.name}>"


def _materials_against(scene, folder):
    """The dict scene with each material file it names (a region's value that is a path: it has a folder or ends
    in .json) made absolute against `folder`, as a scene file's are against its own."""
    materials = scene.get("materials")
    if not isinstance(materials, dict):
        return scene

    def absolute(value):
        if isinstance(value, str) and (_os.sep in value or value.endswith(".json")) and not _os.path.isabs(value):
            return _os.path.join(folder, value)
        # A region given as a map names its file under `file:` (it was read from the temporary folder, which is
        # gone: an outside check).
        if isinstance(value, dict) and isinstance(value.get("file"), str) and not _os.path.isabs(value["file"]):
            return dict(value, file=_os.path.join(folder, value["file"]))
        return value

    return dict(scene, materials={region: absolute(value) for region, value in materials.items()})


def _scene_json(scene):
    """A scene dict as JSON (which is YAML), NumPy's scalars and arrays as the numbers and lists they hold (an outside
    check's np.int64 step count was "Object of type int64 is not JSON serializable"); anything else is named with
    its key."""
    def plain(value, key):
        if isinstance(value, dict):
            return {k: plain(v, f"{key}.{k}" if key else str(k)) for k, v in value.items()}
        if isinstance(value, (list, tuple)):
            return [plain(v, f"{key}[{i}]") for i, v in enumerate(value)]
        if hasattr(value, "tolist") and hasattr(value, "dtype"):  # a NumPy scalar or array
            return value.tolist()
        if value is None or isinstance(value, (str, bool, int, float)):
            return value
        if isinstance(value, _os.PathLike):
            return _os.fspath(value)
        raise ConfigError(f"the scene dict: {key} = {value!r} is a {type(value).__name__}: a scene holds numbers, "
                          "strings, booleans, lists and maps")
    return _json.dumps(plain(scene, ""))


class Scene:
    """A simulation scene (graphs/scenes/*.yaml, docs/scenes.md) made runnable: a path, or a dict laid out as the
    YAML file (a relative `base:` is resolved against base_dir, default the current folder)."""

    def __init__(self, scene, base_dir=None):
        self._name = None  # a dict read through a temporary file: what `file` says instead of that gone file
        self._read_through = None  # that temporary file, named in errors raised later as the dict
        if isinstance(scene, Scene):
            self._s, self._name, self._read_through = scene._s, scene._name, scene._read_through
        elif isinstance(scene, dict):
            scene = dict(scene)
            base = scene.get("base")
            if base is None:
                try:
                    self._s = _drape._Scene.from_text(_scene_json(scene), "the scene dict")  # JSON is YAML
                except (ConfigError, Error) as e:  # (its one line of JSON: the dict is what to name)
                    raise type(e)(str(e).replace("the scene dict:1: ", "the scene dict: ")) from None
            else:
                # drape follows `base:` only from a file: the dict goes through one (JSON is YAML).
                # A relative base: against base_dir, else the current folder, else a shipped scene by name.
                path = _os.path.join(base_dir or _os.getcwd(), _os.fspath(base))
                if not (base_dir or _os.path.isabs(path) and _os.path.exists(path)):
                    path = find_file(_os.fspath(base))
                scene["base"] = _os.path.abspath(path)
                # A material file is read against the scene file's folder: a dict's folder is base_dir, or the
                # current folder (the temporary file's would find nothing: an outside check).
                scene = _materials_against(scene, base_dir or _os.getcwd())
                with _tempfile.TemporaryDirectory(prefix="drape-scene-") as tmp:
                    path = _os.path.join(tmp, "scene.yaml")
                    with open(path, "w") as f:
                        f.write(_scene_json(scene))
                    try:
                        self._s = _drape._Scene.from_file(path)
                        self._name = f"the scene dict (base: {scene['base']})"
                        self._read_through = path
                    except (ConfigError, Error) as e:
                        # The temporary file (one line of JSON) is gone: the dict is what to name.
                        text = str(e).replace(path + ":1: ", "the scene dict: ").replace(path, "the scene dict")
                        raise type(e)(text) from None
        elif isinstance(scene, (str, _os.PathLike)):
            self._s = _drape._Scene.from_file(_os.fspath(scene))
        else:
            raise TypeError(f"scene: expected a path or a dict, got {type(scene).__name__}")

    def __getattr__(self, name):
        if name in ("_s", "_name", "_read_through"):  # (a Scene whose construction failed: no recursion through __getattr__)
            raise AttributeError(name)
        return getattr(self._s, name)

    @property
    def file(self):
        """The scene's file; a dict's is named as the dict (with the scene it is based on), not as the temporary
        file drape read it through, which is gone (an outside check)."""
        return self._name or self._s.file

    def energies(self, body_vertices=None):
        """{effect name: drape.Energy} bound to the garment and this body (default: the scene's own target body)."""
        with self._errors_name_the_dict():
            native = self._s.energies(body_vertices)
        return {name: Energy(native, name) for name in native.names}

    @_contextlib.contextmanager
    def _errors_name_the_dict(self):
        """Errors raised after construction name a dict as the dict, not the temporary file drape read it through
        (gone: "/tmp/drape-scene-.../scene.yaml: the cloth has no stretching", an outside check)."""
        try:
            yield
        except (ConfigError, Error) as e:
            if not self._read_through or self._read_through not in str(e):
                raise
            text = str(e).replace(self._read_through + ":1: ", "the scene dict: ").replace(self._read_through, "the scene dict")
            raise type(e)(text) from None

    def simulate(self, body_vertices=None, start_garment=None, measure_penetration=True, start_body=None, pose=None):
        """Drapes the garment on the body (default: the scene's own): a dict of garment and body (float64
        [N, 3]), energies {effect: J}, total_energy, converged, residual, stationarity, sliding and slip_ratio (with
        friction: whether the garment still slid over the body in the last step, and its fastest contact's slip
        relative to the slip friction holds), penetration (p),
        crossings, self_crossings (the garment's edges through its own faces), steps, iterations, seconds, and `unsettled` (why, when not converged). As drape simulate
        does: a body standing away from where the body model's bodies stand is draped there and the results moved
        back (a warning says so); with `size: auto` the body wears the size its girth needs (`size`: the choice
        and its measurements, `garment_size`: the size). The morph starts from start_body (default: the body
        the garment is dressed on, `fit_body`: the scene body model's mean shape for the regular size, the body of
        its girth for a larger one). pose: joint angles in degrees, {"shoulder_abduction": 20} or
        "shoulder_abduction=20,elbow_flexion=30" (docs/poses.md), instead of the scene's own `body: {pose: ...}`; a
        given body is taken as unposed and posed too; the result's `pose` is the pose draped. The GIL is released."""
        with self._errors_name_the_dict():
            return self._s.simulate(body_vertices, start_garment, measure_penetration, start_body, pose)

    def __repr__(self):
        return f"<drape.Scene {self.file}: {', '.join(self._s.effects)}>"


def simulate(scene, body_vertices=None, **options):
    """drape.simulate(scene path or dict or Scene, body_vertices) -> the garment and per-effect energies
    (Scene.simulate)."""
    return Scene(scene).simulate(body_vertices, **options)


def generate(scene, out, count, bmi=(10, 65), height=1.75, sex=1.0, girths=0.0, seed=0, shard=(0, 1), threads=0,
             progress=True, poses="scene", pose_ranges=None):
    """Generates (or resumes) a dataset of simulated drapes into `out`, as `drape generate` does and with the same
    bytes for the same arguments (one service behind both): `count` bodies drawn uniformly in bmi, height and sex
    (a number, or a (lo, hi) range; sex draws one of its two ends), girths spread as a fraction of the body model's
    range, the 8:1:1 split from `seed`; shard=(i, N) makes part i of N. Returns a dict of what was done:
    samples, not_settled, penetrating, crossing, crossing_itself (the global indices of the drapes whose garment
    crosses itself, on a resume those of earlier runs too: checked_again of them read back from the file), resumed_with (done by an earlier run), threads, ranges, already_finished (True when `out` was
    finished by this same request: nothing is simulated; a finished `out` made otherwise raises ConfigError).
    poses="scene" drapes every body in the scene's pose (its A-pose when it has none); poses="draw" draws each
    body's pose from the body model's pose space (docs/poses.md), with pose_ranges ({"shoulder_abduction": (60, 90)}
    or "shoulder_abduction=60:90") replacing sampling ranges; the joint angles are stored (Dataset.read's "pose").
    The GIL is released while it runs; a progress bar goes to stderr unless progress=False."""
    if poses not in ("scene", "draw"):
        raise ConfigError(f"poses={poses!r}: expected 'scene' or 'draw'")
    if isinstance(pose_ranges, dict):
        pose_ranges = ",".join(f"{k}={lo}:{hi}" for k, (lo, hi) in pose_ranges.items())
    # Named here: the native call's own refusal of a negative number is a
    # dump of its private signature.
    for name, value in (("count", count), ("seed", seed), ("threads", threads)):
        if isinstance(value, bool) or int(value) != value or int(value) < 0:
            raise ConfigError(f"{name}={value!r}: expected a whole number >= 0")
    return _drape._generate(_native_scene(scene), _os.fspath(out), int(count), bmi, height, sex, float(girths),
                            int(seed), tuple(shard), int(threads), bool(progress), poses == "draw",
                            pose_ranges or "")


def _native_scene(scene):
    return Scene(scene)._s


_Model_optimize = Model.optimize


def _optimize(self, scene, body_vertices, body_params=None, iterations=100, learning_rate=1e-4, pose=None,
              garment_size=None):
    return _Model_optimize(self, _native_scene(scene), body_vertices, body_params, iterations, learning_rate, pose,
                           garment_size)


_optimize.__doc__ = _Model_optimize.__doc__
Model.optimize = _optimize


# What each native object is, at a glance (they are not picklable nor
# deep-copyable: docs/python.md, "Objects").
def _model_repr(self):
    return (f"<drape.Model {self.file or '(untrained)'}: {self.garment_vertex_count} garment vertices, "
            f"body {self.body_vertex_count} vertices>")


def _body_model_repr(self):
    return (f"<drape.BodyModel {self.name!r}: {self.vertex_count} vertices, "
            f"{len(self.shape_names)} shape parameters>")


def _dataset_repr(self):
    files = self.files
    where = files[0] if len(files) == 1 else f"{len(files)} files from {files[0]}"
    return f"<drape.Dataset {where}: {len(self)} done samples of {self.size}>"


Model.__repr__ = _model_repr
BodyModel.__repr__ = _body_model_repr
Dataset.__repr__ = _dataset_repr


def _dataset_getitem(self, i):
    """The i-th done sample in file order (negative i counts from the end): a dict of body float32 [Nb, 3],
    garment float32 [Ng, 3], body_params float32 [P], split (0 train, 1 val, 2 test) and index (the sample's
    row in the file), and in a posed dataset pose float32 [A] (degrees, layout["pose_angles"]). A slice gives a
    list of them."""
    done = self.indices()
    if isinstance(i, slice):
        return [self[k] for k in range(*i.indices(len(done)))]
    k = _operator.index(i)
    if k < 0:
        k += len(done)
    if not 0 <= k < len(done):
        raise IndexError(f"sample {i} of a dataset of {len(done)} done samples")
    batch = self.read([int(done[k])])
    sample = {"body": batch["body"][0], "garment": batch["garment"][0], "body_params": batch["body_params"][0],
              "split": int(batch["split"][0]), "index": int(batch["indices"][0])}
    if "pose" in batch:
        sample["pose"] = batch["pose"][0]
    return sample


Dataset.__getitem__ = _dataset_getitem


def write_obj(path, vertices, faces):
    """A small OBJ writer (vertices [N, 3], 0-based faces [F, 3]), written to a temporary file and renamed.
    Coordinates are written with 17 significant digits (as the drape program writes them), so a float32 or float64
    array reads back bit for bit; %.6f lost up to 5e-7 m of a float32 body."""
    vertices = _np.asarray(vertices, dtype=_np.float64)
    faces = _np.asarray(faces)
    if vertices.ndim != 2 or vertices.shape[1] != 3:
        raise ConfigError(f"vertices: expected [N, 3], got shape {list(vertices.shape)}")
    if not _np.isfinite(vertices).all():  # (an OBJ of "nan" no reader takes back)
        raise ConfigError(f"vertices: {int((~_np.isfinite(vertices)).any(axis=-1).sum())} rows hold NaN or inf")
    if faces.ndim != 2 or faces.shape[1] != 3:
        raise ConfigError(f"faces: expected [F, 3] 0-based vertex indices, got shape {list(faces.shape)}")
    # Indices are whole numbers within the vertices: a float index was cut, and
    # one out of range or negative was written as it stood (OBJ reads a
    # negative index as counted from the end), making a file no reader takes.
    if faces.size and not _np.issubdtype(faces.dtype, _np.integer):
        if not _np.issubdtype(faces.dtype, _np.floating) or not _np.array_equal(faces, _np.round(faces)):
            raise ConfigError(f"faces: expected whole vertex indices, got {faces.dtype} values that are not")
        faces = faces.astype(_np.int64)
    if faces.size and (faces.min() < 0 or faces.max() >= len(vertices)):
        bad = int(faces.min()) if faces.min() < 0 else int(faces.max())
        raise ConfigError(f"faces: index {bad} is outside the {len(vertices)} vertices (0-based: 0 to {len(vertices) - 1})")
    tmp = f"{path}.tmp{_os.getpid()}"
    try:
        with open(tmp, "w") as f:
            _np.savetxt(f, vertices, fmt="v %.17g %.17g %.17g")
            _np.savetxt(f, faces + 1, fmt="f %d %d %d")
        _os.replace(tmp, path)
    finally:
        if _os.path.exists(tmp):  # (a failed write leaves nothing beside the path)
            _os.remove(tmp)
