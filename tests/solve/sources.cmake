target_sources(sdflow_tests PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/test_blas_threads.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_carried_ordering.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_single_precision_factor.cpp)
