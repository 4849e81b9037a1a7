target_sources(sdflow_tests PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/test_point_normals.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_advancing_front.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_holes.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_reconstruct_apart.cpp)
