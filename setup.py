"""Builds the probrobscene extension with the project's CMake (pip install --no-build-isolation .).

setuptools cannot compile a CMake project itself, so build_ext configures a build directory
(PRS_CMAKE_BUILD_DIR to reuse one, e.g. build/; else build-python/cmake), builds the target
prs_python and copies the extension into the wheel. Needs cmake, ninja and pybind11-dev
(scripts/setup.sh); no package index is contacted.
"""

import os
import pathlib
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE_DIR = pathlib.Path(__file__).resolve().parent


class CMakeBuild(build_ext):
    def build_extension(self, ext: Extension) -> None:
        reuse = os.environ.get("PRS_CMAKE_BUILD_DIR")
        build_dir = pathlib.Path(reuse or SOURCE_DIR / "build-python" / "cmake").resolve()
        configure = ["cmake", "-S", str(SOURCE_DIR), "-B", str(build_dir),
                     "-DPRS_BUILD_PYTHON=ON", f"-DPython_EXECUTABLE={sys.executable}"]
        if not reuse:  # a build of its own: only what the extension needs, optimised
            configure += ["-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
                          "-DPRS_BUILD_BENCHMARKS=OFF"]
        subprocess.run(configure, check=True)
        jobs = os.environ.get("PRS_JOBS", "2")
        subprocess.run(["cmake", "--build", str(build_dir), "--target", "prs_python", "-j", jobs],
                       check=True)
        built = build_dir / "python" / "probrobscene" / pathlib.Path(self.get_ext_filename("_core"))
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(built, target)


setup(
    ext_modules=[Extension("probrobscene._core", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": "build-python"}},
)
