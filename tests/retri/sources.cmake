target_sources(sdflow_tests PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/point_samples.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_point_normals.cpp)
