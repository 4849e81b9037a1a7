target_sources(sdflow_toolbox PRIVATE
  sdflow/flow/blas_threads.cpp
  sdflow/flow/carried_ordering.cpp
  sdflow/flow/checkpoint.cpp
  sdflow/flow/degraded_elements.cpp
  sdflow/flow/intersection_guard.cpp
  sdflow/flow/parameter_schema.cpp
  sdflow/flow/parameters.cpp
  sdflow/flow/retriangulation.cpp
  sdflow/flow/run_lock.cpp
  sdflow/flow/scheme.cpp
  sdflow/flow/simulation.cpp
  sdflow/flow/single_precision_factor.cpp
  sdflow/flow/solver.cpp
  sdflow/flow/supernodal_cholesky.cpp
  sdflow/flow/surface_diffusion.cpp
  sdflow/flow/time_step.cpp
  sdflow/flow/volume.cpp)
