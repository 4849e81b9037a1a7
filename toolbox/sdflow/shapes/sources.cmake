target_sources(sdflow_toolbox PRIVATE
  sdflow/shapes/implicit.cpp
  sdflow/shapes/dumbbell.cpp
  sdflow/shapes/catalogue.cpp
  sdflow/shapes/packing.cpp
  sdflow/shapes/expression.cpp
  sdflow/shapes/marching_tetrahedra.cpp
  sdflow/shapes/mesher.cpp)
