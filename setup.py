"""The build behind `pip install .` (pyproject.toml): CMake builds the module's one target, partreg_python, and
its compiled _partreg lands in the wheel beside python/partreg's files.

Environment:
  PARTREG_BUILD_DIR   an existing CMake build tree of this source (`build`): reused, only the module is built
                      in it (it must have been configured for the same Python version); default: a fresh tree
                      under pip's temporary build folder, without the GUI and the tests.
  CMAKE_BUILD_PARALLEL_LEVEL   compile jobs (CMake's own variable), 2 when unset.
"""
import os
import pathlib
import re
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE = pathlib.Path(__file__).resolve().parent


def project_version():
    """The version of CMakeLists.txt's project() (one place: partreg/version.hpp is generated from it)."""
    text = (SOURCE / "CMakeLists.txt").read_text()
    return re.search(r"project\(partreg VERSION ([0-9.]+)", text).group(1)


class CMakeBuild(build_ext):
    """Builds partreg_python with CMake, then copies the module where setuptools packs it."""

    def build_extension(self, ext):
        given = os.environ.get("PARTREG_BUILD_DIR")
        build_dir = pathlib.Path(given).resolve() if given else pathlib.Path(self.build_temp).resolve() / "cmake"
        if not (build_dir / "CMakeCache.txt").exists():
            self.spawn(["cmake", "-S", str(SOURCE), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
                        "-DPARTREG_BUILD_UI=OFF", "-DPARTREG_BUILD_TESTS=OFF", "-DPARTREG_BUILD_BENCHMARKS=OFF",
                        "-DPARTREG_BUILD_PYTHON=ON", f"-DPython_EXECUTABLE={sys.executable}"])
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", "2")
        self.spawn(["cmake", "--build", str(build_dir), "--target", "partreg_python", "--parallel", jobs])
        built = sorted((build_dir / "python" / "partreg").glob("_partreg*.so"))
        if not built:
            sys.exit(f"setup.py: CMake built no _partreg module in {build_dir}/python/partreg")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], target)


setup(
    version=project_version(),
    packages=["partreg"],
    package_dir={"partreg": "python/partreg"},
    package_data={"partreg": ["__init__.pyi", "py.typed"]},
    ext_modules=[Extension("partreg._partreg", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    zip_safe=False,
    options={"build": {"build_base": "build/pip"}},  # beside, not inside, the CMake tree `build`
)
