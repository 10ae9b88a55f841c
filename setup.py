"""The Python package beamid: `pip install --no-build-isolation .` in a virtual environment made with
`python3 -m venv --system-site-packages` (Debian's NumPy, setuptools and pybind11; no PyPI).

The extension beamid._core is the CMake target beamid_python_module of this project (python/src/core_module.cc over the same
static libraries as the program), built in setuptools' build_temp with the interpreter that runs pip, so the module
matches it; CMAKE_BUILD_PARALLEL_LEVEL sets the build's jobs (default: the machine's cores).
"""
import os
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

HERE = os.path.dirname(os.path.abspath(__file__))


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        package_dir = os.path.dirname(os.path.abspath(self.get_ext_fullpath(ext.name)))
        build_dir = os.path.abspath(os.path.join(self.build_temp, "cmake"))
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        subprocess.run(["cmake", "-S", HERE, "-B", build_dir, "-DCMAKE_BUILD_TYPE=Release", "-DBEAMID_BENCHMARKS=OFF",
                        "-DBUILD_TESTING=OFF",
                        f"-DPython3_EXECUTABLE={sys.executable}", f"-DBEAMID_PYTHON_DIR={package_dir}"], check=True)
        subprocess.run(["cmake", "--build", build_dir, "--target", "beamid_python_module", "-j", jobs], check=True)


# The metadata (name, version from VERSION, licence, dependencies) is in pyproject.toml; this file adds the extension.
setup(
    ext_modules=[CMakeExtension("beamid._core")],
    cmdclass={"build_ext": CMakeBuild},
)
