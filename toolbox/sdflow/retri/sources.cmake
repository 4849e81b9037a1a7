# Re-triangulation toolbox (docs/design.md §3): one algorithm per file.
file(GLOB _sdflow_retri CONFIGURE_DEPENDS ${CMAKE_CURRENT_LIST_DIR}/*.cpp)
target_sources(sdflow_toolbox PRIVATE ${_sdflow_retri})
