//! The factorisation's thread policy (solve/blas_threads.h): one thread below the crossover and for
//! solves, the environment's cap above it, and OpenBLAS and CHOLMOD's OpenMP loops actually told.
#include "sdflow/flow/scheme.h"
#include "sdflow/solve/blas_threads.h"
#include "sdflow/solve/solver.h"
#include "support/analytic_meshes.h"

#include <gtest/gtest.h>

#include <dlfcn.h>

#include <cstdlib>
#include <thread>

namespace sdflow {
namespace {

//! OpenBLAS's own thread count, or -1 when the loaded BLAS is not OpenBLAS.
int openblas_threads()
{
  using GetThreads = int (*)();
  const auto get = reinterpret_cast<GetThreads>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
  return get == nullptr ? -1 : get();
}

//! libgomp's max-active-levels, or -1 when no OpenMP runtime is loaded.
int openmp_active_levels()
{
  using GetLevels = int (*)();
  const auto get = reinterpret_cast<GetLevels>(dlsym(RTLD_DEFAULT, "omp_get_max_active_levels"));
  return get == nullptr ? -1 : get();
}

TEST(BlasThreads, one_thread_below_the_crossover_and_the_cap_above)
{
  if (std::getenv("SDFLOW_BLAS_THREADS") != nullptr)
    GTEST_SKIP() << "SDFLOW_BLAS_THREADS fixes the count";
  const BlasThreadPolicy policy{.single_thread_below = 1000};
  EXPECT_EQ(blas_threads_for(999, policy), 1);
  const int above = blas_threads_for(1000, policy);
  EXPECT_GE(above, 1);
  if (std::getenv("OPENBLAS_NUM_THREADS") == nullptr && std::getenv("OMP_NUM_THREADS") == nullptr) {
    EXPECT_EQ(above, static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
  }
}

TEST(BlasThreads, the_loaded_openblas_is_told_and_solves_leave_it_on_one_thread)
{
  ASSERT_TRUE(set_factorisation_threads(2)) << "openblas_set_num_threads not found: CHOLMOD's BLAS is not OpenBLAS";
  if (openblas_threads() < 0)
    GTEST_SKIP() << "no openblas_get_num_threads";
  const Mesh mesh = analytic::icosphere(3);
  const FlowOperators op = flow_operators(mesh);
  // Crossover at 0: the factorisation may use every thread; the solve after it must not.
  FlowSolver solver({.blas = {.single_thread_below = 0}});
  solver.solve({op.laplacian, op.areas, op.held, 1e-3}, op.rhs);
  EXPECT_EQ(openblas_threads(), 1);
}

// CHOLMOD's OpenMP loops ask for 4 threads whatever the count: on one thread no region may be active.
TEST(BlasThreads, cholmod_openmp_loops_follow_the_thread_count)
{
  if (openmp_active_levels() < 0)
    GTEST_SKIP() << "no OpenMP runtime loaded (CHOLMOD built without OpenMP)";
  set_factorisation_threads(2);
  EXPECT_EQ(openmp_active_levels(), 1);
  set_factorisation_threads(1);
  EXPECT_EQ(openmp_active_levels(), 0);
  set_factorisation_threads(2);
  const Mesh mesh = analytic::icosphere(3);
  const FlowOperators op = flow_operators(mesh);
  FlowSolver solver; // below the crossover: the factorisation runs on one thread, and so do its loops
  solver.solve({op.laplacian, op.areas, op.held, 1e-3}, op.rhs);
  EXPECT_EQ(openmp_active_levels(), 0);
}

} // namespace
} // namespace sdflow
