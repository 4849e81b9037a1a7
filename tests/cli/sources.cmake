if(TARGET sdflow)
  target_sources(sdflow_tests PRIVATE
    ${CMAKE_CURRENT_LIST_DIR}/test_run.cpp
    ${CMAKE_CURRENT_LIST_DIR}/test_shape.cpp
    ${CMAKE_CURRENT_LIST_DIR}/test_stats.cpp)
endif()
