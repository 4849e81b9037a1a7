target_sources(sdflow_toolbox PRIVATE
  sdflow/remesh/remesh.cpp
  sdflow/remesh/star_projection.cpp)
