// OpenCL error handling: the only place that includes the OpenCL C header for the whole
// project (other modules reach OpenCL through this module's wrappers only).
#pragma once
#ifndef CL_TARGET_OPENCL_VERSION
#define CL_TARGET_OPENCL_VERSION 120
#endif
#include <CL/cl.h>

#include <string>

#include "core/error.hpp"

namespace sgnlf::cl {

// An OpenCL call failed: carries the call, the error code and its name.
class ClError : public Error {
 public:
  ClError(const std::string& call, cl_int code, const std::string& detail = "");
  cl_int code() const { return code_; }

 private:
  cl_int code_;
};

// A kernel failed to build: carries the device, the options and the full build log.
class BuildError : public Error {
 public:
  BuildError(const std::string& what, std::string log) : Error(what), log_(std::move(log)) {}
  const std::string& log() const { return log_; }

 private:
  std::string log_;
};

// No OpenCL platform or no device matched the selection.
class DeviceError : public Error {
 public:
  using Error::Error;
};

const char* error_name(cl_int code);

inline void check(cl_int code, const char* call, const std::string& detail = "") {
  if (code != CL_SUCCESS) throw ClError(call, code, detail);
}

}  // namespace sgnlf::cl
