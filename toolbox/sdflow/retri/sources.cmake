target_sources(sdflow_toolbox PRIVATE
  sdflow/retri/star_projection.cpp
  sdflow/retri/remesh.cpp)
