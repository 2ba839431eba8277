// StagedUpload (staged_upload.hpp): non-blocking writes from an owned host copy.
#include "cl/staged_upload.hpp"

namespace sgnlf::cl {

StagedUpload& StagedUpload::operator=(StagedUpload&& o) noexcept {
  if (this != &o) {
    try {
      wait();
    } catch (...) {  // a failed wait leaves nothing to protect: the command is gone
    }
    data_ = std::move(o.data_);
    staged_ = o.staged_;
    done_ = std::move(o.done_);
  }
  return *this;
}

StagedUpload::~StagedUpload() {
  try {
    wait();
  } catch (...) {  // destructors do not throw; the device reported an error already
  }
}

void StagedUpload::write(Buffer& dst, size_t offset) {
  done_ = dst.write_async(data_.data(), staged_, offset);
}

void StagedUpload::wait() {
  if (!done_) return;
  done_.wait();
  done_ = Event();
}

}  // namespace sgnlf::cl
