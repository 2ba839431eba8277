// JobRecord: stages recorded and found again; a folder with another request refused, naming
// the key that differs; a damaged record refused.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "core/config.hpp"
#include "core/error.hpp"
#include "support/test_device.hpp"
#include "workflow/job_record.hpp"
#include "workflow/reconstruct.hpp"

using namespace sgnlf;
namespace fs = std::filesystem;

TEST_CASE("JobRecord keeps finished stages and refuses another request", "[workflow][record]") {
  const fs::path dir = test::temp_dir("job_record");
  const std::string path = (dir / "job.json").string();
  const Json req{{"scans", "a"}, {"seed", 1}, {"load_options", {{"frames", 4}}}};
  {
    workflow::JobRecord r(path, req);
    CHECK_FALSE(r.done("one"));
    r.finish("one", Json{{"x", 1}});
  }
  workflow::JobRecord again(path, req);
  CHECK(again.done("one"));
  CHECK(again.stage("one").at("x") == 1);
  CHECK_FALSE(again.done("two"));
  CHECK_THROWS_AS(again.stage("two"), Error);

  Json other = req;
  other["seed"] = 2;
  try {
    workflow::JobRecord r(path, other);
    FAIL("another request was accepted");
  } catch (const ConfigError& e) {
    CHECK(std::string(e.what()).find("seed") != std::string::npos);
    CHECK(std::string(e.what()).find(path) != std::string::npos);
  }
  other = req;
  other["load_options"]["frames"] = 5;
  CHECK_THROWS_WITH(workflow::JobRecord(path, other), Catch::Contains("load_options.frames"));

  std::ofstream(path) << "[1, 2]";
  CHECK_THROWS_AS(workflow::JobRecord(path, req), IoError);
}

TEST_CASE("reconstruct request: one scans folder named another way is the same request",
          "[workflow][record]") {
  // canonical: the working directory below is read back with symbolic links resolved
  const fs::path dir = fs::canonical(test::temp_dir("reconstruct_request"));
  fs::create_directories(dir / "scans");
  const fs::path cwd = fs::current_path();
  fs::current_path(dir);
  workflow::ReconstructRequest a, b, c, other;
  a.scans = (dir / "scans").string();
  b.scans = "scans/";
  c.scans = "./scans/../scans";
  other.scans = "scans2";
  const Json ja = a.to_json(), jb = b.to_json(), jc = c.to_json(), jo = other.to_json();
  fs::current_path(cwd);
  CHECK(ja.at("scans") == (dir / "scans").lexically_normal().string());
  CHECK(jb == ja);
  CHECK(jc == ja);
  CHECK(jo != ja);
}
