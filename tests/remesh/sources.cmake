target_sources(sdflow_tests PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/test_crease_edges.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_exact_refinement.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_kept_boundary_sizing.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_local_remesh.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_remesh.cpp)
