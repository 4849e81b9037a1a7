target_sources(sdflow_tests PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/test_bvh.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_closest_point_grid.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_intersect.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_local_thickness.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_spatial_order.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_winding_number.cpp)
