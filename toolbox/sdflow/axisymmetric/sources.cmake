target_sources(sdflow_toolbox PRIVATE
  sdflow/axisymmetric/curve.cpp
  sdflow/axisymmetric/step.cpp
  sdflow/axisymmetric/evolution.cpp
  sdflow/axisymmetric/initial_curves.cpp)
