target_sources(sdflow_tests PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/analytic_meshes.cpp
  ${CMAKE_CURRENT_LIST_DIR}/exact_intersections.cpp
  ${CMAKE_CURRENT_LIST_DIR}/exact_reference.cpp
  ${CMAKE_CURRENT_LIST_DIR}/json_query.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mesh_checks.cpp
  ${CMAKE_CURRENT_LIST_DIR}/point_samples.cpp)
# The exact rational reference of the intersection tests uses GMP (libgmp-dev), and the brute-force
# intersection checks use Shewchuk's exact orient3d exported by TetGen: both for tests only.
find_path(SDFLOW_GMPXX_INCLUDE_DIR gmpxx.h REQUIRED)
find_library(SDFLOW_GMPXX_LIBRARY gmpxx REQUIRED)
find_library(SDFLOW_GMP_LIBRARY gmp REQUIRED)
target_include_directories(sdflow_tests SYSTEM PRIVATE ${SDFLOW_GMPXX_INCLUDE_DIR})
target_link_libraries(sdflow_tests PRIVATE ${SDFLOW_GMPXX_LIBRARY} ${SDFLOW_GMP_LIBRARY} sdflow_tetgen)
