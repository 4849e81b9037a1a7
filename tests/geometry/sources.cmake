target_sources(sdflow_tests PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/test_angle.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_normals.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_curvature.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_cotangent_curvature.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_principal_curvature.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_shape_operator.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_weighted_curvature.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_laplacian.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_measures.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_topology.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_quality.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_mesh_arrays.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_anisotropy.cpp
  ${CMAKE_CURRENT_LIST_DIR}/test_formula_anisotropy.cpp)
