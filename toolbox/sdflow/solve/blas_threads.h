#pragma once
//! \file blas_threads.h
//! \brief How many threads CHOLMOD's supernodal factorisation uses, in its BLAS and in its own OpenMP
//! loops (docs/design.md §10).
//! CHOLMOD's OpenMP loops ask for a fixed team of 4, which oversubscribed small machines: they run
//! on the calling thread when the count is one. A second BLAS thread gains 3-21% of a factorisation
//! and 4-16% of a step while burning 1.2-2x the CPU (docs/design.md §10). The policy: one thread
//! below `BlasThreadPolicy::single_thread_below` unknowns, all hardware threads above, and one
//! thread again for the triangular solves and CG, which are memory-bound.
//! Environment overrides: SDFLOW_BLAS_THREADS=n fixes n threads for every factorisation;
//! OPENBLAS_NUM_THREADS (or OMP_NUM_THREADS) caps the count, as OpenBLAS itself does at start-up.

namespace sdflow {

struct BlasThreadPolicy {
  //! Factorisations of fewer unknowns (vertices) run on one thread (docs/design.md §10 says what
  //! this value rests on; bench/bench_blas_threads.cpp measures the crossover).
  long single_thread_below = 400000;
};

//! The thread count for a factorisation of `unknowns` unknowns under `policy` and the environment.
int blas_threads_for(long unknowns, const BlasThreadPolicy& policy = {});

//! Sets the threads of CHOLMOD's numeric factorisation: the BLAS's count if the loaded BLAS can be
//! told (OpenBLAS's openblas_set_num_threads, looked up at run time so that any BLAS links), and
//! whether CHOLMOD's own OpenMP loops may run in parallel (serial for one thread). Returns false
//! when the BLAS cannot be told.
bool set_factorisation_threads(int threads);

} // namespace sdflow
