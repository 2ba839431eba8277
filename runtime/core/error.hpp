// Project error types. The library throws; only apps/ turns errors into exit codes.
#pragma once
#include <stdexcept>
#include <string>

namespace sgnlf {

// Base of every error the library throws.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

// Invalid configuration: names the config (file or section), the key and the value.
class ConfigError : public Error {
 public:
  using Error::Error;
};

// Bad or missing input data: names the file and, where known, the line or byte offset.
class IoError : public Error {
 public:
  using Error::Error;
};

// A run that diverged (NaN/Inf loss) or cannot continue numerically.
class NumericError : public Error {
 public:
  using Error::Error;
};

// Throws sgnlf::Error with `what` when `cond` is false; used for shape/argument validation.
void require(bool cond, const std::string& what);

}  // namespace sgnlf
