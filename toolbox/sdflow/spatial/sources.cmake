# Spatial queries and exact geometry: the toolbox that retri/, remesh/, reconstruct/, shapes/ and
# the verbs share.
target_sources(sdflow_toolbox PRIVATE
  sdflow/spatial/predicates.cpp
  sdflow/spatial/bvh.cpp
  sdflow/spatial/intersect.cpp
  sdflow/spatial/closest_point_grid.cpp
  sdflow/spatial/spatial_order.cpp
  sdflow/spatial/nearest_points.cpp
  sdflow/spatial/local_thickness.cpp
  sdflow/spatial/winding_number.cpp)
