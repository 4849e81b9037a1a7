target_sources(sdflow_tests PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/test_blas_threads.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_boundary_condition.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_carried_ordering.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_degraded_elements.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_exact_kinetics.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_look_ahead.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_parameter_schema.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_parameters.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_retriangulation.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_run_control.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_samples.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_scheme.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_simulation.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_single_precision_factor.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_surface_diffusion.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_time_step.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_volume.cpp)
