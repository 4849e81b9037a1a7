target_sources(sdflow_toolbox PRIVATE
  sdflow/flow/scheme.cpp
  sdflow/flow/solver.cpp)
