"""Builds rigidpy's extension rigidpy._engine (src/pyengine) for `pip install` (pyproject.toml
has the rest): CMake configures the project's build directory (RIGID_BUILD_DIR, default build/,
the one setup.sh uses) and builds the target `_engine` there, and the module is copied into the
package. RIGID_PREBUILT_ENGINE=PATH installs an extension already built instead (the install test,
tests/python/test_install.py, which must not compile the engine again)."""
import os
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        prebuilt = os.environ.get("RIGID_PREBUILT_ENGINE")
        if prebuilt:
            shutil.copyfile(prebuilt, target)
            return
        build_dir = os.path.join(ROOT, os.environ.get("RIGID_BUILD_DIR", "build"))
        configure = ["cmake", "-S", ROOT, "-B", build_dir, "-DRIGID_PYTHON=ON", f"-DPYTHON_EXECUTABLE={sys.executable}"]
        if not os.path.isfile(os.path.join(build_dir, "CMakeCache.txt")):
            configure.append("-DCMAKE_BUILD_TYPE=Release")
        configure += os.environ.get("RIGID_CMAKE_ARGS", "").split()
        subprocess.run(configure, check=True)
        jobs = os.environ.get("JOBS", str(os.cpu_count() or 1))
        subprocess.run(["cmake", "--build", build_dir, "--target", "_engine", "-j", jobs], check=True)
        built = os.path.join(build_dir, "python", "rigidpy", os.path.basename(target))
        if not os.path.isfile(built):
            raise RuntimeError(f"CMake did not build {built} (is pybind11-dev installed? setup.sh installs it)")
        shutil.copyfile(built, target)


# setuptools' own build directory would be build/, CMake's: kept inside it, apart
setup(ext_modules=[Extension("rigidpy._engine", sources=[])], cmdclass={"build_ext": CMakeBuild},
      options={"build": {"build_base": os.path.join("build", "setuptools")}})
