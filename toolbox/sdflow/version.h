#pragma once
//! \file version.h
//! \brief Which sdflow this is: its version and the git commit it was built from, as run.toml and
//! `sdflow --version` record them.

namespace sdflow {

//! The version, "MAJOR.MINOR.PATCH" (CMake's project version).
const char* version();

//! The git commit the library was built from, read when it was built: 40 hex digits, with
//! "-dirty" appended when tracked files differed from that commit; "unknown" outside a git checkout.
const char* git_commit();

} // namespace sdflow
