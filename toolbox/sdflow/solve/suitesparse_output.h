#pragma once
//! \file suitesparse_output.h
//! \brief SuiteSparse (CHOLMOD, SPQR) prints its warnings and errors through one global printf
//! (SuiteSparse_config.printf_func, stdout by default), e.g. "CHOLMOD warning: matrix not positive
//! definite". The library never prints: this sends that text to the logger instead (debug level:
//! every failure it describes also comes back as a status that the solver turns into SolverFailure).

namespace sdflow {

//! Route SuiteSparse's printing to logger(); idempotent and thread-safe. The solvers call it
//! before their first use of CHOLMOD or SPQR.
void route_suitesparse_output();

} // namespace sdflow
