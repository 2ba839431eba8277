#include "cl/memory.hpp"

#include <algorithm>
#include <functional>
#include <numeric>

#include "cl/runtime.hpp"

namespace sgnlf::cl {

void Event::wait() const {
  if (!e_) return;
  cl_event e = e_.get();
  check(clWaitForEvents(1, &e), "clWaitForEvents");
}

double Event::elapsed_ms() const {
  wait();
  cl_ulong t0 = 0, t1 = 0;
  check(clGetEventProfilingInfo(e_.get(), CL_PROFILING_COMMAND_START, sizeof t0, &t0, nullptr),
        "clGetEventProfilingInfo");
  check(clGetEventProfilingInfo(e_.get(), CL_PROFILING_COMMAND_END, sizeof t1, &t1, nullptr),
        "clGetEventProfilingInfo");
  return double(t1 - t0) * 1e-6;
}

Buffer::Buffer(Runtime& rt, size_t bytes, cl_mem_flags flags) : rt_(&rt), bytes_(bytes) {
  if (bytes == 0) throw Error("cl::Buffer: zero-sized buffer requested");
  cl_int rc = CL_SUCCESS;
  cl_mem m = clCreateBuffer(rt.context(), flags, bytes, nullptr, &rc);
  check(rc, "clCreateBuffer", std::to_string(bytes) + " bytes on " + rt.device().name);
  mem_ = MemHandle(m);
}

void Buffer::write(const void* src, size_t bytes, size_t offset) {
  if (offset + bytes > bytes_)
    throw Error("cl::Buffer::write: " + std::to_string(offset + bytes) + " bytes past a " +
                std::to_string(bytes_) + "-byte buffer");
  if (bytes == 0) return;
  if (rt_->trace()) rt_->trace()->add_transfer(false, bytes);
  check(clEnqueueWriteBuffer(rt_->queue(), mem_.get(), CL_TRUE, offset, bytes, src, 0, nullptr,
                             nullptr),
        "clEnqueueWriteBuffer");
}

Event Buffer::write_async(const void* src, size_t bytes, size_t offset) {
  if (offset + bytes > bytes_)
    throw Error("cl::Buffer::write_async: " + std::to_string(offset + bytes) + " bytes past a " +
                std::to_string(bytes_) + "-byte buffer");
  if (bytes == 0) return Event();
  if (rt_->trace()) rt_->trace()->add_async_transfer(bytes);
  cl_event e = nullptr;
  check(clEnqueueWriteBuffer(rt_->queue(), mem_.get(), CL_FALSE, offset, bytes, src, 0, nullptr,
                             &e),
        "clEnqueueWriteBuffer (non-blocking)");
  return Event(e);
}

void Buffer::read(void* dst, size_t bytes, size_t offset) const {
  if (offset + bytes > bytes_)
    throw Error("cl::Buffer::read: " + std::to_string(offset + bytes) + " bytes past a " +
                std::to_string(bytes_) + "-byte buffer");
  if (bytes == 0) return;
  if (rt_->trace()) rt_->trace()->add_transfer(true, bytes);
  check(clEnqueueReadBuffer(rt_->queue(), mem_.get(), CL_TRUE, offset, bytes, dst, 0, nullptr,
                            nullptr),
        "clEnqueueReadBuffer");
}

void Buffer::fill_zero() {
  const cl_uchar zero = 0;
  check(clEnqueueFillBuffer(rt_->queue(), mem_.get(), &zero, 1, 0, bytes_, 0, nullptr, nullptr),
        "clEnqueueFillBuffer");
}

void Buffer::copy_from(const Buffer& src, size_t bytes, size_t src_offset, size_t dst_offset) {
  if (src_offset + bytes > src.bytes_ || dst_offset + bytes > bytes_)
    throw Error("cl::Buffer::copy_from: range past the end of a buffer");
  check(clEnqueueCopyBuffer(rt_->queue(), src.get(), mem_.get(), src_offset, dst_offset, bytes, 0,
                            nullptr, nullptr),
        "clEnqueueCopyBuffer");
}

Kernel::Kernel(Runtime& rt, cl_program program, const std::string& name) : rt_(&rt), name_(name) {
  cl_int rc = CL_SUCCESS;
  cl_kernel k = clCreateKernel(program, name.c_str(), &rc);
  check(rc, "clCreateKernel", name);
  k_ = KernelHandle(k);
}

void Kernel::set_arg(cl_uint i, const Buffer& b) {
  cl_mem m = b.get();
  set_raw(i, sizeof(cl_mem), &m);
  if (buffer_bytes_.size() <= i) buffer_bytes_.resize(i + 1, 0);
  buffer_bytes_[i] = b.bytes();
}

void Kernel::set_arg(cl_uint i, const LocalMem& m) {
  if (i < buffer_bytes_.size()) buffer_bytes_[i] = 0;
  check(clSetKernelArg(k_.get(), i, m.bytes, nullptr), "clSetKernelArg",
        name_ + " argument " + std::to_string(i) + " (local memory)");
}

void Kernel::set_raw(cl_uint i, size_t size, const void* value) {
  if (i < buffer_bytes_.size()) buffer_bytes_[i] = 0;  // set_arg(Buffer) sets it after
  check(clSetKernelArg(k_.get(), i, size, value), "clSetKernelArg",
        name_ + " argument " + std::to_string(i));
}

Event Kernel::launch(std::vector<size_t> global, std::vector<size_t> local,
                     size_t trace_elements) {
  if (global.empty() || global.size() > 3) throw Error("Kernel::launch: 1 to 3 dimensions");
  for (size_t g : global)
    if (g == 0) return Event();  // nothing to do
  if (!local.empty() && local.size() != global.size())
    throw Error("Kernel::launch: local and global sizes differ in dimensions");
  cl_event e = nullptr;
  check(clEnqueueNDRangeKernel(rt_->queue(), k_.get(), cl_uint(global.size()), nullptr,
                               global.data(), local.empty() ? nullptr : local.data(), 0, nullptr,
                               &e),
        "clEnqueueNDRangeKernel", name_);
  Event ev(e);
  if (LaunchTrace* t = rt_->trace())
    t->launches.push_back(
        {name_, std::accumulate(global.begin(), global.end(), size_t(1), std::multiplies<>()),
         buffer_bytes_.empty() ? 0 : *std::max_element(buffer_bytes_.begin(), buffer_bytes_.end()),
         trace_elements});
  if (rt_->profiling()) {
    ev.wait();
    rt_->record(name_, ev.elapsed_ms());
  }
  return ev;
}

}  // namespace sgnlf::cl
