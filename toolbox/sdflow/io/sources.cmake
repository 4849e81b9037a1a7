target_sources(sdflow_toolbox PRIVATE
  sdflow/io/io.cpp
  sdflow/io/base64.cpp
  sdflow/io/binary_scalar.cpp
  sdflow/io/text.cpp
  sdflow/io/off.cpp
  sdflow/io/obj.cpp
  sdflow/io/ply.cpp
  sdflow/io/stl.cpp
  sdflow/io/vertex_field.cpp
  sdflow/io/vtk.cpp
  sdflow/io/vtp.cpp
  sdflow/io/point_cloud.cpp
  sdflow/io/repair.cpp
  sdflow/io/triangulate_polygon.cpp
  sdflow/io/validate.cpp)
