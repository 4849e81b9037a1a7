target_sources(sdflow_tests PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/temp_dir.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_round_trip.cpp)
