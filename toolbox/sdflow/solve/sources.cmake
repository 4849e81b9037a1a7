target_sources(sdflow_toolbox PRIVATE
  sdflow/solve/blas_threads.cpp
  sdflow/solve/carried_ordering.cpp
  sdflow/solve/single_precision_factor.cpp
  sdflow/solve/solver.cpp
  sdflow/solve/suitesparse_output.cpp
  sdflow/solve/supernodal_cholesky.cpp)
