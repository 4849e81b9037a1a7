# SuiteSparse (CHOLMOD, SPQR) and TetGen ship no CMake package files in Debian: this finds them and
# defines the imported targets sdflow::suitesparse and sdflow::tetgen. The build includes it from
# SdflowDependencies.cmake, and it is installed beside sdflowConfig.cmake, which includes it so a
# consumer links what the static sdflow::toolbox needs. Sets sdflow_SYSTEM_LIBRARIES_MISSING to the
# libraries not found (empty when all are), and fails only through the includer.

set(sdflow_SYSTEM_LIBRARIES_MISSING "")
if(TARGET sdflow::suitesparse AND TARGET sdflow::tetgen)
  return() # already defined in this directory (find_package(sdflow) called twice)
endif()

find_path(SUITESPARSE_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
set(_sdflow_suitesparse_libraries "")
foreach(_lib cholmod spqr amd colamd camd ccolamd metis suitesparseconfig)
  find_library(SDFLOW_${_lib}_LIBRARY ${_lib})
  list(APPEND _sdflow_suitesparse_libraries ${SDFLOW_${_lib}_LIBRARY})
endforeach()
find_path(TETGEN_INCLUDE_DIR tetgen.h)
find_library(TETGEN_LIBRARY tet)

foreach(_var SUITESPARSE_INCLUDE_DIR SDFLOW_cholmod_LIBRARY SDFLOW_spqr_LIBRARY SDFLOW_amd_LIBRARY
             SDFLOW_colamd_LIBRARY SDFLOW_camd_LIBRARY SDFLOW_ccolamd_LIBRARY SDFLOW_metis_LIBRARY
             SDFLOW_suitesparseconfig_LIBRARY TETGEN_INCLUDE_DIR TETGEN_LIBRARY)
  if(NOT ${_var})
    list(APPEND sdflow_SYSTEM_LIBRARIES_MISSING ${_var})
  endif()
endforeach()
if(sdflow_SYSTEM_LIBRARIES_MISSING)
  return()
endif()

add_library(sdflow::suitesparse INTERFACE IMPORTED)
target_include_directories(sdflow::suitesparse SYSTEM INTERFACE ${SUITESPARSE_INCLUDE_DIR})
target_link_libraries(sdflow::suitesparse INTERFACE ${_sdflow_suitesparse_libraries})

add_library(sdflow::tetgen INTERFACE IMPORTED)
target_include_directories(sdflow::tetgen SYSTEM INTERFACE ${TETGEN_INCLUDE_DIR})
target_compile_definitions(sdflow::tetgen INTERFACE TETLIBRARY)
target_link_libraries(sdflow::tetgen INTERFACE ${TETGEN_LIBRARY})
