// Typed errors. `main` catches them, prints one line and returns 1 (bad input, failed I/O) — flags that
// do not parse are CLI11's and exit 2.
#pragma once

#include <stdexcept>
#include <string>

namespace fcc {

// Base of every error the tool reports as one line.
struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A file that cannot be read or is not what it claims: the message names the file, what is wrong
// and, where it helps, what is valid.
struct InputError : Error {
  using Error::Error;
};

// A value that is out of its valid range (an isovalue that is not finite, a zero size, ...).
struct ValueError : Error {
  using Error::Error;
};

// Writing an output failed (nothing is left behind).
struct OutputError : Error {
  using Error::Error;
};

}  // namespace fcc
