// JobRecord (see job_record.hpp).
#include "workflow/job_record.hpp"

#include <filesystem>

#include "core/config.hpp"
#include "core/error.hpp"

namespace sgnlf::workflow {
namespace fs = std::filesystem;

namespace {

// The first key (dotted path) where `a` and `b` differ, "" when equal.
std::string first_difference(const Json& a, const Json& b, const std::string& at) {
  if (a.is_object() && b.is_object()) {
    for (auto it = a.begin(); it != a.end(); ++it) {
      const std::string k = at.empty() ? it.key() : at + "." + it.key();
      if (!b.contains(it.key())) return k;
      if (std::string d = first_difference(it.value(), b.at(it.key()), k); !d.empty()) return d;
    }
    for (auto it = b.begin(); it != b.end(); ++it)
      if (!a.contains(it.key())) return at.empty() ? it.key() : at + "." + it.key();
    return "";
  }
  return a == b ? "" : (at.empty() ? "(the whole request)" : at);
}

}  // namespace

JobRecord::JobRecord(std::string path, Json request) : path_(std::move(path)) {
  if (fs::exists(path_)) {
    j_ = load_json_file(path_);
    if (!j_.is_object() || !j_.contains("request") || !j_.contains("stages") ||
        !j_.at("stages").is_object())
      throw IoError(path_ + ": not a job record (expected the keys request and stages)");
    const std::string d = first_difference(j_.at("request"), request, "");
    if (!d.empty())
      throw ConfigError(path_ + ": the folder holds a job with another request (" + d + ": " +
                        (j_.at("request").contains(d) ? j_.at("request").at(d).dump() : "…") +
                        " there); use a new output folder");
  } else {
    j_ = Json{{"request", std::move(request)}, {"stages", Json::object()}};
  }
}

bool JobRecord::done(const std::string& stage) const { return j_.at("stages").contains(stage); }

const Json& JobRecord::stage(const std::string& stage) const {
  require(done(stage), path_ + ": stage " + stage + " has not run");
  return j_.at("stages").at(stage);
}

void JobRecord::finish(const std::string& stage, Json result) {
  j_["stages"][stage] = std::move(result);
  write();
}

void JobRecord::set(const std::string& key, Json value) {
  require(key != "request" && key != "stages", path_ + ": '" + key + "' is not settable");
  j_[key] = std::move(value);
  write();
}

void JobRecord::write() const {
  const fs::path p(path_);
  if (p.has_parent_path()) fs::create_directories(p.parent_path());
  const std::string tmp = path_ + ".tmp";
  write_json_file(tmp, j_);
  fs::rename(tmp, path_);
}

}  // namespace sgnlf::workflow
