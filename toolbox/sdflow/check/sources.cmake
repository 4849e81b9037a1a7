target_sources(sdflow_toolbox PRIVATE
  sdflow/check/span.cpp
  sdflow/check/tetgen_volume.cpp
  sdflow/check/statistics.cpp)
