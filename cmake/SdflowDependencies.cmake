# Locates sdflow's dependencies, all from Debian bookworm packages (see scripts/install-deps.sh).

find_package(OpenMesh REQUIRED)          # libopenmesh-dev: OpenMeshCore, OpenMeshTools
find_package(Eigen3 3.4 REQUIRED NO_MODULE)  # libeigen3-dev
find_package(spdlog REQUIRED)            # libspdlog-dev
find_package(fmt REQUIRED)               # libfmt-dev
find_package(tomlplusplus REQUIRED)      # libtomlplusplus-dev (TOML scenarios, JSON output)
find_package(nanoflann REQUIRED)         # libnanoflann-dev (k nearest neighbours)
find_package(TBB REQUIRED)               # libtbb-dev
find_package(muparser REQUIRED)          # libmuparser-dev (user level-set formulas)
find_package(EXPAT REQUIRED)             # libexpat1-dev (reading .vtp files)

# SuiteSparse (CHOLMOD, SPQR) and TetGen ship no CMake package files in Debian: sdflow::suitesparse
# and sdflow::tetgen come from a file the installed package uses too. tests/ and bench/ use the
# old names.
include(sdflowSystemLibraries)
if(sdflow_SYSTEM_LIBRARIES_MISSING)
  message(FATAL_ERROR "sdflow: not found: ${sdflow_SYSTEM_LIBRARIES_MISSING} "
                      "(Debian: libsuitesparse-dev libmetis-dev libtet1.5-dev; scripts/install-deps.sh)")
endif()
add_library(sdflow_suitesparse ALIAS sdflow::suitesparse)
add_library(sdflow_tetgen ALIAS sdflow::tetgen)
