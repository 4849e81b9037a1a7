target_sources(sdflow_tests PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/test_exact_intersections.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_marching_tetrahedra.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_mesher.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_packing.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_shapes.cpp)
