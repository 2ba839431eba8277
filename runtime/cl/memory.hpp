// RAII wrappers for OpenCL objects used by the whole project: buffers, events, kernels,
// programs. No other module calls cl* functions directly.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "cl/error.hpp"

namespace sgnlf::cl {

class Runtime;

// Owning handle for any reference-counted OpenCL object.
template <typename H, cl_int (*Release)(H)>
class Handle {
 public:
  Handle() = default;
  explicit Handle(H h) : h_(h) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& o) noexcept : h_(std::exchange(o.h_, nullptr)) {}
  Handle& operator=(Handle&& o) noexcept {
    if (this != &o) {
      reset();
      h_ = std::exchange(o.h_, nullptr);
    }
    return *this;
  }
  ~Handle() { reset(); }
  void reset() {
    if (h_) Release(h_);
    h_ = nullptr;
  }
  H get() const { return h_; }
  explicit operator bool() const { return h_ != nullptr; }

 private:
  H h_ = nullptr;
};

using ContextHandle = Handle<cl_context, clReleaseContext>;
using QueueHandle = Handle<cl_command_queue, clReleaseCommandQueue>;
using MemHandle = Handle<cl_mem, clReleaseMemObject>;
using ProgramHandle = Handle<cl_program, clReleaseProgram>;
using KernelHandle = Handle<cl_kernel, clReleaseKernel>;
using EventHandle = Handle<cl_event, clReleaseEvent>;

// A completed or pending command; profiling times in milliseconds (queue has profiling on).
class Event {
 public:
  Event() = default;
  explicit Event(cl_event e) : e_(e) {}
  void wait() const;
  double elapsed_ms() const;  // end - start of the command
  cl_event get() const { return e_.get(); }
  explicit operator bool() const { return bool(e_); }

 private:
  EventHandle e_;
};

// A device buffer of `bytes` bytes. Transfers are blocking unless stated otherwise.
class Buffer {
 public:
  Buffer() = default;
  Buffer(Runtime& rt, size_t bytes, cl_mem_flags flags = CL_MEM_READ_WRITE);
  size_t bytes() const { return bytes_; }
  cl_mem get() const { return mem_.get(); }
  explicit operator bool() const { return bool(mem_); }

  void write(const void* src, size_t bytes, size_t offset = 0);
  // Non-blocking write: enqueued behind the queue's earlier commands and returned at once; `src`
  // must stay valid and unchanged until the returned event has completed (cl::StagedUpload
  // keeps its host copy so). Recorded in the launch trace as an asynchronous transfer.
  Event write_async(const void* src, size_t bytes, size_t offset = 0);
  void read(void* dst, size_t bytes, size_t offset = 0) const;
  void fill_zero();
  void copy_from(const Buffer& src, size_t bytes, size_t src_offset = 0, size_t dst_offset = 0);

  template <typename T>
  void write_vec(const std::vector<T>& v, size_t offset_elems = 0) {
    write(v.data(), v.size() * sizeof(T), offset_elems * sizeof(T));
  }
  template <typename T>
  std::vector<T> read_vec(size_t n, size_t offset_elems = 0) const {
    std::vector<T> v(n);
    read(v.data(), n * sizeof(T), offset_elems * sizeof(T));
    return v;
  }
  template <typename T>
  std::vector<T> read_all() const {
    return read_vec<T>(bytes_ / sizeof(T));
  }
  // A buffer created from host data.
  template <typename T>
  static Buffer from(Runtime& rt, const std::vector<T>& v) {
    Buffer b(rt, std::max<size_t>(1, v.size()) * sizeof(T));
    if (!v.empty()) b.write_vec(v);
    return b;
  }

 private:
  Runtime* rt_ = nullptr;
  MemHandle mem_;
  size_t bytes_ = 0;
};

// Local (work-group) memory argument of a given size.
struct LocalMem {
  size_t bytes;
};

// A kernel with its arguments. set_args() sets every argument in one place, in order.
class Kernel {
 public:
  Kernel() = default;
  Kernel(Runtime& rt, cl_program program, const std::string& name);
  const std::string& name() const { return name_; }
  cl_kernel get() const { return k_.get(); }
  Runtime* runtime() const { return rt_; }

  template <typename... A>
  Kernel& set_args(const A&... args) {
    cl_uint i = 0;
    (set_arg(i++, args), ...);
    return *this;
  }
  void set_arg(cl_uint i, const Buffer& b);
  void set_arg(cl_uint i, const LocalMem& m);
  template <typename T, typename = std::enable_if_t<std::is_trivially_copyable_v<T>>>
  void set_arg(cl_uint i, const T& v) {
    set_raw(i, sizeof(T), &v);
  }

  // Enqueues over an N-d range (global sizes rounded up by the caller); local may be empty.
  // trace_elements: the 4-byte words the launch works on, for the launch trace (TracedLaunch::
  // elements) where its largest buffer argument over-counts them; 0 = not given.
  Event launch(std::vector<size_t> global, std::vector<size_t> local = {},
               size_t trace_elements = 0);

 private:
  void set_raw(cl_uint i, size_t size, const void* value);
  Runtime* rt_ = nullptr;
  KernelHandle k_;
  std::string name_;
  // Bytes of the buffer bound at each argument index (0: not a buffer), for the launch trace.
  std::vector<size_t> buffer_bytes_;
};

inline size_t round_up(size_t n, size_t m) { return (n + m - 1) / m * m; }

}  // namespace sgnlf::cl
