// SPDX-License-Identifier: GPL-3.0-or-later
//! \file error.h
//! Typed exceptions thrown by the library. The library never calls exit() or
//! abort() on user input: it throws one of these, with a message a user can
//! act on, and the command-line front end turns it into an exit code
//! (see apps/subfab/exit_codes.h).
#pragma once

#include <stdexcept>
#include <string>

namespace subfab {

//! Base class of every error subfab throws on purpose.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

//! A file cannot be opened, read, parsed or written.
//! Message names the file and, where known, the line or byte offset.
class IoError : public Error {
 public:
  using Error::Error;
};

//! The input mesh cannot be used by the requested algorithm
//! (not closed, non-manifold, self-intersecting, NaN coordinates, ...).
class InvalidMeshError : public Error {
 public:
  using Error::Error;
};

//! An option or argument has a value the algorithm cannot work with.
class InvalidArgumentError : public Error {
 public:
  using Error::Error;
};

//! An algorithm could not reach a valid result on a valid input
//! (it says why). Never used for bad input.
class AlgorithmError : public Error {
 public:
  using Error::Error;
};

}  // namespace subfab
