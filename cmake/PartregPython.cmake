# The Python module `partreg` (python/), built with Debian's pybind11 against the system interpreter
# (python3-numpy, python3-pytest and python3-open3d are Debian packages: /usr/bin/python3 sees them, a
# python3 earlier on PATH may not). PARTREG_BUILD_PYTHON defaults to ON when pybind11 is found.
if(NOT Python_EXECUTABLE AND EXISTS /usr/bin/python3)
  set(Python_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "The Python interpreter the module is built for")
endif()
set(PYBIND11_FINDPYTHON ON)  # CMake's FindPython with the interpreter above, not pybind11's older search
find_package(pybind11 CONFIG QUIET)
option(PARTREG_BUILD_PYTHON "Build the Python module (python/)" ${pybind11_FOUND})
if(NOT PARTREG_BUILD_PYTHON)
  return()
endif()
if(NOT pybind11_FOUND)
  message(FATAL_ERROR "PARTREG_BUILD_PYTHON needs pybind11 (Debian pybind11-dev: scripts/install_deps.sh)")
endif()
add_subdirectory(python)
