"""Builds the Python package heavytop: python/heavytop/*.py and the compiled module
heavytop._core, which CMake builds from this very source tree (the target heavytop_python of
python/CMakeLists.txt, as MuJoCo's Python package does), so pip and the CMake build cannot
differ. Metadata: pyproject.toml; the version is CMakeLists.txt's project(VERSION).

    python3 -m venv --system-site-packages .venv && .venv/bin/pip install --no-build-isolation .

Everything is built in a temporary folder (removed afterwards), never in the source tree,
which may be read-only and whose build/ is the developers' CMake build. Set
HEAVYTOP_PIP_BUILD_DIR to a folder of your own to keep the build there and make the next
install incremental. CMAKE_BUILD_PARALLEL_LEVEL sets the compile jobs (default: every core).
"""
import atexit
import glob
import os
import re
import shutil
import subprocess
import sys
import tempfile

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext
from setuptools.command.build_py import build_py

ROOT = os.path.dirname(os.path.abspath(__file__))


def cmake_project_version():
    with open(os.path.join(ROOT, "CMakeLists.txt"), encoding="utf-8") as f:
        match = re.search(r"project\(\s*heavytop\s+VERSION\s+([0-9][0-9.]*)", f.read())
    if not match:
        sys.exit("setup.py: no project(heavytop VERSION x.y.z) in CMakeLists.txt")
    return match.group(1)


def build_folder():
    """setuptools' build_base and egg_base: a folder of its own, outside the source tree."""
    folder = os.environ.get("HEAVYTOP_PIP_BUILD_DIR")
    if folder:
        folder = os.path.abspath(folder)
        if os.path.commonpath([folder, ROOT]) == ROOT:
            sys.exit(f"setup.py: HEAVYTOP_PIP_BUILD_DIR={folder} is inside the source tree; choose a folder outside it")
        os.makedirs(folder, exist_ok=True)
        return folder
    folder = tempfile.mkdtemp(prefix="heavytop-pip-")
    atexit.register(shutil.rmtree, folder, ignore_errors=True)
    return folder


class CMakeExtension(Extension):
    """An extension module that a CMake target builds."""

    def __init__(self, name, target):
        super().__init__(name, sources=[])
        self.target = target


class CMakeBuild(build_ext):
    """Configures the source tree in build_temp, builds the extension's target, and copies the
    module where setuptools expects it (the wheel's heavytop/ folder)."""

    def run(self):
        if self.inplace:
            sys.exit("setup.py: an in-place (editable) build would put the compiled module into the source tree; "
                     "build with CMake instead and use PYTHONPATH=build/python")
        if shutil.which("cmake") is None:
            sys.exit("setup.py: cmake is needed to build heavytop (Debian: apt-get install cmake)")
        super().run()

    def build_extension(self, ext):
        build_dir = os.path.join(os.path.abspath(self.build_temp), "cmake")
        configure = [
            "cmake", "-S", ROOT, "-B", build_dir,
            "-DCMAKE_BUILD_TYPE=Release",
            "-DHEAVYTOP_BUILD_CLI=OFF",
            "-DHEAVYTOP_BUILD_TESTS=OFF",
            "-DHEAVYTOP_BUILD_BENCHMARKS=OFF",
            "-DHEAVYTOP_BUILD_PYTHON=ON",
            "-DHEAVYTOP_BUILD_SYMBOLIC=ON",  # derive() is part of the module
            "-DHEAVYTOP_INSTALL=OFF",
            f"-DPython3_EXECUTABLE={sys.executable}",
        ]
        build = ["cmake", "--build", build_dir, "--target", ext.target]
        if "CMAKE_BUILD_PARALLEL_LEVEL" not in os.environ:
            build += ["--parallel", str(self.parallel or os.cpu_count() or 1)]
        for command in (configure, build):
            print(" ".join(command), flush=True)
            subprocess.run(command, check=True)

        # python/CMakeLists.txt puts the module into <build>/python/heavytop/.
        built = glob.glob(os.path.join(build_dir, "python", "heavytop", ext.name.split(".")[-1] + "*.so"))
        if len(built) != 1:
            sys.exit(f"setup.py: expected one {ext.name} module in {build_dir}/python/heavytop, found {built}")
        destination = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(destination), exist_ok=True)
        shutil.copyfile(built[0], destination)


def example_files():
    """examples/*.toml, *.csv and meshes/*, relative to examples/: what heavytop.example_file(name)
    finds in the package (the CMake build copies the same files, python/CMakeLists.txt)."""
    folder = os.path.join(ROOT, "examples")
    found = [p for pattern in ("*.toml", "*.csv", os.path.join("meshes", "*"))
             for p in glob.glob(os.path.join(folder, pattern)) if os.path.isfile(p)]
    return sorted(os.path.relpath(p, folder) for p in found)


class BuildPy(build_py):
    """The package's Python files, and the examples' data in heavytop/examples/ (copied into the
    build folder, never into the source tree)."""

    def run(self):
        super().run()
        for name in example_files():
            destination = os.path.join(self.build_lib, "heavytop", "examples", name)
            os.makedirs(os.path.dirname(destination), exist_ok=True)
            shutil.copyfile(os.path.join(ROOT, "examples", name), destination)


BUILD = build_folder()

setup(
    version=cmake_project_version(),
    packages=["heavytop"],
    package_dir={"heavytop": "python/heavytop"},
    package_data={"heavytop": ["py.typed", "*.pyi"]},
    ext_modules=[CMakeExtension("heavytop._core", target="heavytop_python")],
    cmdclass={"build_ext": CMakeBuild, "build_py": BuildPy},
    zip_safe=False,
    options={
        "build": {"build_base": BUILD},
        "egg_info": {"egg_base": BUILD},
    },
)
