target_sources(sdflow_toolbox PRIVATE
  sdflow/retri/predicates.cpp
  sdflow/retri/bvh.cpp
  sdflow/retri/intersect.cpp
  sdflow/retri/surface_union.cpp)
