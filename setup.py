"""pip install of the Python module: `pip install --no-build-isolation .`
builds eqhb/_eqhb with CMake for the interpreter that runs pip (its headers,
its extension suffix) and installs it with the package python/eqhb.

Offline and with what Debian ships: setuptools (and wheel) of the running
environment, CMake, a C++17 compiler, pybind11-dev and the libraries the
project needs (./run.sh test installs them all). Only the libraries and the
module are built (no command, benchmark or tests), in build-python/ beside
the sources; EQHB_PIP_BUILD_DIR chooses another folder, EQHB_CMAKE_ARGS adds
CMake options (e.g. "-DEQHB_WITH_CERES=OFF")."""
import os
import pathlib
import re
import shlex
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent
# setuptools' egg-info goes there (options below) and must exist first.
(ROOT / "build-python").mkdir(exist_ok=True)
VERSION = re.search(r"project\(eqhb VERSION (\S+)", (ROOT / "CMakeLists.txt").read_text()).group(1)


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = pathlib.Path(os.environ.get("EQHB_PIP_BUILD_DIR", ROOT / "build-python")).resolve()
        build.mkdir(parents=True, exist_ok=True)
        # One build folder serves one interpreter at a time: another one
        # (another venv, pyenv) configures afresh, the objects kept.
        marker = build / "python-executable.txt"
        if marker.exists() and marker.read_text() != sys.executable:
            (build / "CMakeCache.txt").unlink(missing_ok=True)
        configure = ["cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                     f"-DPython_EXECUTABLE={sys.executable}", "-DEQHB_BUILD_PYTHON=ON", "-DEQHB_BUILD_CLI=OFF",
                     "-DEQHB_BUILD_BENCH=OFF", "-DEQHB_BUILD_TESTS=OFF", "-DEQHB_INSTALL=OFF"]
        env = dict(os.environ)
        if shutil.which("ccache"):
            configure += ["-DCMAKE_CXX_COMPILER_LAUNCHER=ccache", "-DCMAKE_C_COMPILER_LAUNCHER=ccache"]
            # Paths relative to the sources, so that a build folder at the
            # same depth (build/, build-python/) shares the compiled objects.
            env.setdefault("CCACHE_BASEDIR", str(ROOT))
        configure += shlex.split(os.environ.get("EQHB_CMAKE_ARGS", ""))
        self._run(configure, env)
        marker.write_text(sys.executable)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        self._run(["cmake", "--build", str(build), "--target", "eqhb_python", "-j", jobs], env)
        suffix = sysconfig.get_config_var("EXT_SUFFIX")
        built = build / "python" / "eqhb" / f"_eqhb{suffix}"
        if not built.exists():
            raise RuntimeError(f"CMake did not produce {built}: is pybind11 built for this Python "
                               f"({sys.executable})? See the CMake output above.")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)

    @staticmethod
    def _run(command, env):
        print("eqhb:", " ".join(command), flush=True)
        subprocess.run(command, check=True, env=env)


setup(
    name="eqhb",
    version=VERSION,
    description="Periodic vibrations with dry friction and contact by equality-based harmonic balance",
    long_description=(ROOT / "README.md").read_text(encoding="utf-8"),
    long_description_content_type="text/markdown",
    license="BSD-3-Clause",
    python_requires=">=3.8",
    install_requires=["numpy"],
    packages=["eqhb"],
    package_dir={"eqhb": "python/eqhb"},
    ext_modules=[CMakeExtension("eqhb._eqhb")],
    cmdclass={"build_ext": CMakeBuild},
    zip_safe=False,
    # setuptools' own files out of the CMake build folder build/.
    options={"build": {"build_base": "build-python/setuptools"},
             "egg_info": {"egg_base": "build-python"}},
)
