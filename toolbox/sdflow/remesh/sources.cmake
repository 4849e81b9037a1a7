target_sources(sdflow_toolbox PRIVATE
  sdflow/remesh/crease_edges.cpp
  sdflow/remesh/exact_refinement.cpp
  sdflow/remesh/face_patch.cpp
  sdflow/remesh/kept_boundary_sizing.cpp
  sdflow/remesh/local_remesh.cpp
  sdflow/remesh/remesh.cpp
  sdflow/remesh/star_projection.cpp)
