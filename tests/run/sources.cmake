target_sources(sdflow_tests PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/test_coarse_input.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_parameter_schema.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_parameters.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_resolution_check.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_run_control.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_run_input.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_samples.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_simulation.cpp)
