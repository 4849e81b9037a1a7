target_sources(sdflow_tests PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/point_samples.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mesh_checks.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_holes.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_point_cloud.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_point_normals.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_reconstruct.cpp)
# The brute-force intersection check uses Shewchuk's exact orient3d exported by TetGen.
target_link_libraries(sdflow_tests PRIVATE sdflow_tetgen)
