#pragma once
//! \file errors.h
//! \brief The exceptions sdflow throws. Every message says what was wrong and where.

#include <stdexcept>
#include <string>

namespace sdflow {

//! Base of every sdflow exception; catch this to handle them all.
class Error : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

//! A file could not be read, parsed or written (the message names the file and line).
class IoError : public Error {
public:
  using Error::Error;
};

//! The environment failed us, not the input: the disk or quota is full, a file grew past the
//! process's limit, the file system is read-only or reports an I/O error. Files written before it
//! stay complete (every write is atomic).
class EnvironmentFailure : public IoError {
public:
  using IoError::IoError;
};

//! A mesh violates a precondition: non-manifold, inconsistently oriented, degenerate, NaN...
class InvalidMesh : public Error {
public:
  using Error::Error;
};

//! A parameter is out of its documented range.
class InvalidParameter : public Error {
public:
  using Error::Error;
};

//! A linear solve or factorisation failed, or a step produced non-finite geometry.
class SolverFailure : public Error {
public:
  using Error::Error;
};

} // namespace sdflow
