# A surface from points: normals, advancing front, hole filling (docs/design.md §3, stages 3-5).
target_sources(sdflow_toolbox PRIVATE
  sdflow/reconstruct/point_normals.cpp
  sdflow/reconstruct/advancing_front.cpp
  sdflow/reconstruct/holes.cpp
  sdflow/reconstruct/reconstruct_apart.cpp)
