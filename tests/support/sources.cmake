target_sources(sdflow_tests PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/analytic_meshes.cpp
  ${CMAKE_CURRENT_LIST_DIR}/exact_intersections.cpp
  ${CMAKE_CURRENT_LIST_DIR}/exact_reference.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mesh_checks.cpp
  ${CMAKE_CURRENT_LIST_DIR}/point_samples.cpp)
# Shewchuk's exact orient3d, exported by TetGen, for the brute-force intersection check.
target_link_libraries(sdflow_tests PRIVATE sdflow_tetgen)
