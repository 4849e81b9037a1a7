target_sources(sdflow_tests PRIVATE ${CMAKE_CURRENT_LIST_DIR}/test_tetgen_volume.cpp ${CMAKE_CURRENT_LIST_DIR}/test_statistics.cpp)
