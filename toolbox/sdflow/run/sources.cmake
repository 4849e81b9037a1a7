target_sources(sdflow_toolbox PRIVATE
  sdflow/run/checkpoint.cpp
  sdflow/run/coarse_input.cpp
  sdflow/run/resolution_check.cpp
  sdflow/run/run_input.cpp
  sdflow/run/run_lock.cpp
  sdflow/run/simulation.cpp)
