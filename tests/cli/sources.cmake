# End-to-end tests of the sdflow command, one file per verb or group of verbs.
if(TARGET sdflow)
  file(GLOB _sdflow_cli_tests CONFIGURE_DEPENDS ${CMAKE_CURRENT_LIST_DIR}/test_*.cpp)
  target_sources(sdflow_tests PRIVATE ${_sdflow_cli_tests})
endif()
