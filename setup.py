"""setuptools backend for the cueplan package: CMake builds the extension cueplan._core
(python/CMakeLists.txt) into the place setuptools installs from, as pybind11's
cmake_example does. The metadata is in pyproject.toml.

Environment: CMAKE_BUILD_PARALLEL_LEVEL (jobs; default 2), CUEPLAN_CMAKE_ARGS (extra
configure arguments), CMAKE_CXX_COMPILER_LAUNCHER (e.g. ccache) are passed through.
"""
import os
import shlex
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


class CMakeExtension(Extension):
    def __init__(self, name: str) -> None:
        super().__init__(name, sources=[])


def pybind11_dir():
    """pybind11's CMake files: from the Python package when the interpreter has it,
    else CMake's own search (Debian's pybind11-dev puts them in /usr/lib/cmake)."""
    try:
        import pybind11
        return pybind11.get_cmake_dir()
    except ImportError:
        return None


class CMakeBuild(build_ext):
    def build_extension(self, ext: CMakeExtension) -> None:
        out = Path(self.get_ext_fullpath(ext.name)).resolve().parent  # .../cueplan
        build = Path(self.build_temp).resolve() / "cmake"
        build.mkdir(parents=True, exist_ok=True)
        config = "Debug" if self.debug else "Release"
        args = [
            f"-DCMAKE_BUILD_TYPE={config}",
            f"-DPython_EXECUTABLE={sys.executable}",
            f"-DCUEPLAN_PYTHON_OUTPUT_DIR={out}",
            "-DCUEPLAN_PYTHON_COPY_PACKAGE=OFF",
            "-DCUEPLAN_BUILD_PYTHON=ON",
            "-DCUEPLAN_BUILD_APPS=OFF",
            "-DCUEPLAN_BUILD_TESTS=OFF",
            "-DCUEPLAN_BUILD_BENCHMARKS=OFF",
        ]
        if pybind11_dir():
            args.append(f"-Dpybind11_DIR={pybind11_dir()}")
        if os.environ.get("CMAKE_CXX_COMPILER_LAUNCHER"):
            args.append(f"-DCMAKE_CXX_COMPILER_LAUNCHER={os.environ['CMAKE_CXX_COMPILER_LAUNCHER']}")
        args += shlex.split(os.environ.get("CUEPLAN_CMAKE_ARGS", ""))
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", "2")
        subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build), *args], check=True)
        subprocess.run(["cmake", "--build", str(build), "--target", "cueplan_core", "-j", jobs], check=True)


setup(ext_modules=[CMakeExtension("cueplan._core")], cmdclass={"build_ext": CMakeBuild})
