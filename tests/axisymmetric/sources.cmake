target_sources(sdflow_tests PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/test_curve.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_initial_curves.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_evolution.cpp)
