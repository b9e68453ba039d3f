#pragma once
/// \file errors.h
/// The exceptions the knitforge library throws. Every message is meant for a
/// user: it names the file, line, element index or option that is wrong and,
/// where there is one, what to do about it. The library never prints and never
/// calls exit(); the CLI turns these into one line on stderr and an exit code.

#include <stdexcept>
#include <string>

namespace knitforge {

/// Base of every knitforge exception.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// An argument or option has a value the function cannot work with
/// (wrong size, NaN, negative length, unknown name, ...).
class InvalidInput : public Error {
 public:
  using Error::Error;
};

/// A mesh or stitch structure has the wrong topology for the operation
/// (non-manifold edge or vertex, inconsistent orientation, not a disk, ...).
class TopologyError : public Error {
 public:
  using Error::Error;
};

/// A numerical solver failed (factorisation not positive definite, no
/// convergence, non-finite result).
class SolverError : public Error {
 public:
  using Error::Error;
};

/// Reading or writing a file failed: cannot open, malformed content
/// (with file and line), or a write that could not be completed.
class IOError : public Error {
 public:
  using Error::Error;
};

}  // namespace knitforge
