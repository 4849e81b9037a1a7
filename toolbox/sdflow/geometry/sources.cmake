target_sources(sdflow_toolbox PRIVATE
  sdflow/geometry/normals.cpp
  sdflow/geometry/curvature.cpp
  sdflow/geometry/cotangent_curvature.cpp
  sdflow/geometry/principal_curvature.cpp
  sdflow/geometry/shape_operator.cpp
  sdflow/geometry/weighted_curvature.cpp
  sdflow/geometry/laplacian.cpp
  sdflow/geometry/cotangent_cache.cpp
  sdflow/geometry/measures.cpp
  sdflow/geometry/material_volume.cpp
  sdflow/geometry/quality.cpp
  sdflow/geometry/topology.cpp
  sdflow/geometry/anisotropy.cpp
  sdflow/geometry/form_sum_anisotropy.cpp
  sdflow/geometry/formula_anisotropy.cpp)
