target_sources(sdflow_toolbox PRIVATE
  sdflow/retri/holes.cpp
  sdflow/retri/point_cloud.cpp
  sdflow/retri/point_normals.cpp
  sdflow/retri/reconstruct.cpp)
