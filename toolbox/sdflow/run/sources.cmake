target_sources(sdflow_toolbox PRIVATE
  sdflow/run/checkpoint.cpp
  sdflow/run/coarse_input.cpp
  sdflow/run/parameter_schema.cpp
  sdflow/run/parameters.cpp
  sdflow/run/resolution_check.cpp
  sdflow/run/run_input.cpp
  sdflow/run/run_lock.cpp
  sdflow/run/schema_retriangulation.cpp
  sdflow/run/schema_run.cpp
  sdflow/run/schema_scheme.cpp
  sdflow/run/schema_time_step.cpp
  sdflow/run/simulation.cpp)
