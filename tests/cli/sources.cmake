if(TARGET sdflow)
  target_sources(sdflow_tests PRIVATE ${CMAKE_CURRENT_LIST_DIR}/test_stats.cpp)
  target_sources(sdflow_tests PRIVATE ${CMAKE_CURRENT_LIST_DIR}/test_retri_verbs.cpp)
endif()
