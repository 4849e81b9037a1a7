# The exact rational reference of the intersection tests uses GMP (libgmp-dev), for tests only.
find_path(SDFLOW_GMPXX_INCLUDE_DIR gmpxx.h REQUIRED)
find_library(SDFLOW_GMPXX_LIBRARY gmpxx REQUIRED)
find_library(SDFLOW_GMP_LIBRARY gmp REQUIRED)
target_include_directories(sdflow_tests SYSTEM PRIVATE ${SDFLOW_GMPXX_INCLUDE_DIR})
target_link_libraries(sdflow_tests PRIVATE ${SDFLOW_GMPXX_LIBRARY} ${SDFLOW_GMP_LIBRARY})
file(GLOB _sdflow_retri_tests CONFIGURE_DEPENDS ${CMAKE_CURRENT_LIST_DIR}/test_*.cpp)
target_sources(sdflow_tests PRIVATE ${CMAKE_CURRENT_LIST_DIR}/exact_reference.cpp ${_sdflow_retri_tests})
