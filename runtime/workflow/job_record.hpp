// The record of a resumable multi-stage job in its folder (RUN/reconstruct.json):
//   {"request": {...}, "stages": {"<name>": {<what the stage reported>}, ...}}
// written atomically after each stage. Opening a folder whose record holds another request is
// refused (ConfigError naming the file and the first key that differs).
#pragma once
#include <string>

#include "core/config.hpp"

namespace sgnlf::workflow {

class JobRecord {
 public:
  // Reads `path` when it exists (checking its request against `request`), else starts empty.
  JobRecord(std::string path, Json request);

  bool done(const std::string& stage) const;
  const Json& stage(const std::string& stage) const;  // Error when not done
  // Marks `stage` done with its result and writes the file.
  void finish(const std::string& stage, Json result);
  // Sets a top-level key beside request and stages (e.g. pose_errors) and writes the file.
  void set(const std::string& key, Json value);
  const Json& json() const { return j_; }
  const std::string& path() const { return path_; }

 private:
  void write() const;
  std::string path_;
  Json j_;
};

}  // namespace sgnlf::workflow
