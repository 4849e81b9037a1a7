# Locates sdflow's dependencies, all from Debian bookworm packages (see scripts/install-deps.sh).

find_package(OpenMesh REQUIRED)          # libopenmesh-dev: OpenMeshCore, OpenMeshTools
find_package(Eigen3 3.4 REQUIRED NO_MODULE)  # libeigen3-dev
find_package(spdlog REQUIRED)            # libspdlog-dev
find_package(fmt REQUIRED)               # libfmt-dev
find_package(tomlplusplus REQUIRED)      # libtomlplusplus-dev (TOML scenarios, JSON output)
find_package(nanoflann REQUIRED)         # libnanoflann-dev (k nearest neighbours)
find_package(TBB REQUIRED)               # libtbb-dev
find_package(muparser REQUIRED)          # libmuparser-dev (user level-set formulas)

# SuiteSparse (CHOLMOD, SPQR) and TetGen ship no CMake package files in Debian.
find_path(SUITESPARSE_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse REQUIRED)
foreach(_lib cholmod spqr amd colamd camd ccolamd suitesparseconfig metis)
  find_library(SDFLOW_${_lib}_LIBRARY ${_lib} REQUIRED)
endforeach()
add_library(sdflow_suitesparse INTERFACE)
target_include_directories(sdflow_suitesparse SYSTEM INTERFACE ${SUITESPARSE_INCLUDE_DIR})
target_link_libraries(sdflow_suitesparse INTERFACE
  ${SDFLOW_cholmod_LIBRARY} ${SDFLOW_spqr_LIBRARY} ${SDFLOW_amd_LIBRARY} ${SDFLOW_colamd_LIBRARY}
  ${SDFLOW_camd_LIBRARY} ${SDFLOW_ccolamd_LIBRARY} ${SDFLOW_metis_LIBRARY}
  ${SDFLOW_suitesparseconfig_LIBRARY})

find_path(TETGEN_INCLUDE_DIR tetgen.h REQUIRED)
find_library(TETGEN_LIBRARY tet REQUIRED)
add_library(sdflow_tetgen INTERFACE)
target_include_directories(sdflow_tetgen SYSTEM INTERFACE ${TETGEN_INCLUDE_DIR})
target_compile_definitions(sdflow_tetgen INTERFACE TETLIBRARY)
target_link_libraries(sdflow_tetgen INTERFACE ${TETGEN_LIBRARY})
