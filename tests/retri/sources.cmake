target_sources(sdflow_tests PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/test_components.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_contact_line_resampling.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_curvature_targets.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_fixed_rim.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_local_surgery.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_pipeline.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_remove_intersections.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_surface_repair.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_surface_union.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_untangle.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_zip_loops.cpp)
