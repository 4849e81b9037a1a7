target_sources(sdflow_tests PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/temp_dir.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_read_errors.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_hostile_files.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_readers.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_repair.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_point_cloud.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_round_trip.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_validate.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_vertex_fields.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_vtp.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_write_atomically.cpp)
