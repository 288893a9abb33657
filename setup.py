"""`pip install --no-build-isolation .`: the drape package built by CMake (docs/python.md, "pip install").

The wheel holds everything inside the package, laid out as a `cmake --install` prefix so that the framework
library finds its plugins and shipped files as it does there:

    drape/__init__.py, torch_bridge.py, ..., _drape.*.so   the package (the module's RUNPATH has $ORIGIN/lib)
    drape/lib/libdrape_framework.so.0                       the framework library
    drape/lib/drape/plugins/libdrape_plugin_*.so            the plugins, found beside the library
    drape/share/drape/{models,graphs}                       the shipped model, scenes, graphs, materials
    drape/bin/drape                                         the drape program (the `drape` console script)

DRAPE_CMAKE_BUILD_DIR=/path/to/build reuses a configured build tree: `cmake --build` of the program and the
module (nothing to do when it is up to date), then `cmake --install` into a staging folder. Without it CMake
configures (tests off, for the Python running pip) and builds in build-pip/cmake, kept for the next install.
DRAPE_BUILD_JOBS: parallel compile jobs (default 2); CMAKE_ARGS: more configure arguments, e.g.
"-DCMAKE_CXX_COMPILER_LAUNCHER=ccache".
"""
import os
import shlex
import shutil
import subprocess
import sys
import sysconfig
import tempfile
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE = Path(__file__).resolve().parent
REUSED = os.environ.get("DRAPE_CMAKE_BUILD_DIR")
# setuptools' own build folders: inside the reused build tree, else build-pip/ (the CMake build is build/).
BUILD_BASE = Path(REUSED).resolve() / "pip" if REUSED else SOURCE / "build-pip"


def run(command, **kwargs):
    print("+", shlex.join(map(str, command)), flush=True)
    subprocess.run([str(c) for c in command], check=True, **kwargs)


class CMakeBuild(build_ext):
    """Builds drape with CMake and copies what the package needs next to the pure-Python files."""

    def run(self):
        cmake = os.environ.get("DRAPE_CMAKE_COMMAND") or shutil.which("cmake")
        if not cmake:
            sys.exit("drape: cmake not found (apt-get install cmake), needed to build the package")
        build_dir = self.reused_build_dir() if REUSED else self.configure(cmake)
        jobs = os.environ.get("DRAPE_BUILD_JOBS", "2")
        run([cmake, "--build", build_dir, "-j", jobs, "--target", "drape", "drape_python"])
        self.check_module(build_dir)
        package = Path(self.get_ext_fullpath("drape._drape")).parent
        with tempfile.TemporaryDirectory(prefix="drape-wheel-") as stage:
            run([cmake, "--install", build_dir, "--prefix", stage], stdout=subprocess.DEVNULL)
            lay_out(Path(stage), package)

    def reused_build_dir(self):
        build_dir = Path(REUSED).resolve()
        if not (build_dir / "CMakeCache.txt").is_file():
            sys.exit(f"drape: DRAPE_CMAKE_BUILD_DIR={REUSED} is not a configured CMake build tree (no CMakeCache.txt)")
        return build_dir

    def configure(self, cmake):
        build_dir = BUILD_BASE / "cmake"
        args = ["-DCMAKE_BUILD_TYPE=Release", "-DDRAPE_BUILD_TESTS=OFF", f"-DPython3_EXECUTABLE={sys.executable}"]
        run([cmake, "-S", SOURCE, "-B", build_dir, *args, *shlex.split(os.environ.get("CMAKE_ARGS", ""))])
        return build_dir

    @staticmethod
    def check_module(build_dir):
        """The build tree's module must be for the Python running pip (a reused tree may be for another)."""
        suffix = sysconfig.get_config_var("EXT_SUFFIX")
        built = sorted((build_dir / "python" / "drape").glob("_drape*.so"))
        if not built:
            sys.exit(f"drape: {build_dir} builds no Python module (CMake said 'drape Python module: skipped': "
                     "apt-get install pybind11-dev python3-dev)")
        if not any(m.name.endswith(suffix) for m in built):
            sys.exit(f"drape: {build_dir} builds {built[0].name}, not a module for this Python ({sys.executable}, "
                     f"*{suffix}); unset DRAPE_CMAKE_BUILD_DIR to build for it")


def lay_out(stage, package):
    """The installed prefix `stage` rearranged into the package folder (see the module docstring)."""
    for old in ("lib", "share", "bin"):
        shutil.rmtree(package / old, ignore_errors=True)
    for old in package.glob("_drape*.so"):
        old.unlink()
    suffix = sysconfig.get_config_var("EXT_SUFFIX")
    modules = list(stage.glob(f"lib*/python*/*-packages/drape/_drape{suffix}"))
    libraries = list(stage.glob("lib*/libdrape_framework.so.*[0-9]"))
    if len(modules) != 1 or not libraries:
        sys.exit(f"drape: cmake --install gave modules {modules} and libraries {libraries}; expected one of each")
    shutil.copy2(modules[0], package)
    libdir = libraries[0].parent
    soname = min(libraries, key=lambda p: len(p.name))  # libdrape_framework.so.0: the name the loader asks for
    (package / "lib").mkdir(parents=True)
    shutil.copy2(soname, package / "lib" / soname.name)  # copy2 follows the symlink: the library itself
    shutil.copytree(libdir / "drape" / "plugins", package / "lib" / "drape" / "plugins", symlinks=False)
    shutil.copytree(stage / "share" / "drape", package / "share" / "drape")
    (package / "bin").mkdir()
    shutil.copy2(stage / "bin" / "drape", package / "bin" / "drape")


BUILD_BASE.mkdir(parents=True, exist_ok=True)
setup(
    ext_modules=[Extension("drape._drape", sources=[])],  # built by CMake; declared so the wheel is platform-specific
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": str(BUILD_BASE)}, "egg_info": {"egg_base": str(BUILD_BASE)}},
)
