// Host data written to a device buffer without waiting for the queue (issue 54, item 4: the
// step's uploads as non-blocking writes). A StagedUpload owns a host copy of what it writes and
// keeps it until the queue has consumed it: stage() (or write_vec()) first waits for this
// upload's previous write, which an in-order queue has long finished by the next step (the
// wait is on that write's event only, not on the queue), then reuses the memory. The
// destructor waits likewise, so the copy never dies under a pending write. The device sees
// exactly the bytes a blocking write would have written.
#pragma once
#include <cstddef>
#include <cstring>
#include <vector>

#include "cl/memory.hpp"

namespace sgnlf::cl {

class StagedUpload {
 public:
  StagedUpload() = default;
  StagedUpload(const StagedUpload&) = delete;
  StagedUpload& operator=(const StagedUpload&) = delete;
  StagedUpload(StagedUpload&& o) noexcept = default;  // the heap copy moves with it
  StagedUpload& operator=(StagedUpload&& o) noexcept;
  ~StagedUpload();

  // Host memory for n elements of T, to fill before write(); waits for the previous write.
  template <typename T>
  T* stage(size_t n) {
    wait();
    data_.resize(n * sizeof(T));
    staged_ = n * sizeof(T);
    return reinterpret_cast<T*>(data_.data());
  }
  // Enqueues a non-blocking write of the staged bytes into `dst` at byte `offset`.
  void write(Buffer& dst, size_t offset = 0);
  // stage() + copy + write() of a whole vector at element `offset_elems` of `dst`.
  template <typename T>
  void write_vec(Buffer& dst, const std::vector<T>& v, size_t offset_elems = 0) {
    T* p = stage<T>(v.size());
    if (!v.empty()) std::memcpy(p, v.data(), v.size() * sizeof(T));
    write(dst, offset_elems * sizeof(T));
  }
  // Waits for the pending write, if any (not for the rest of the queue).
  void wait();
  bool pending() const { return bool(done_); }

 private:
  std::vector<unsigned char> data_;
  size_t staged_ = 0;
  Event done_;
};

}  // namespace sgnlf::cl
