# End-to-end tests of the sdflow command, one file per verb or group of verbs.
if(TARGET sdflow)
  file(GLOB _sdflow_cli_tests CONFIGURE_DEPENDS ${CMAKE_CURRENT_LIST_DIR}/test_*.cpp)
  target_sources(sdflow_tests PRIVATE ${_sdflow_cli_tests})
  # The JSON the verbs print is checked by Python's json module (Debian's interpreter first: a
  # pyenv shim on PATH costs half a second a call).
  if(NOT DEFINED Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
    set(Python3_EXECUTABLE /usr/bin/python3)
  endif()
  find_package(Python3 REQUIRED COMPONENTS Interpreter)
  target_compile_definitions(sdflow_tests PRIVATE SDFLOW_PYTHON3="${Python3_EXECUTABLE}")
endif()
