// The report page opened in headless Chromium, when a chromium binary is on PATH (else a WARN
// and a pass: scripts/setup.sh installs it for the test job). The page's own load-time check
// (report/page.hpp) writes data-images="decoded/total" into the DOM, which --dump-dom returns;
// any console message (a picture that did not decode, a request the page's CSP blocked) fails.
// A page with a broken and a remote picture shows the check catches both.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "report/page.hpp"
#include "report/report.hpp"
#include "report_fixture.hpp"
#include "support/test_device.hpp"

using namespace sgnlf;
namespace fs = std::filesystem;

namespace {

std::string find_chromium() {
  const char* path = std::getenv("PATH");
  if (!path) return "";
  std::stringstream dirs(path);
  std::string d;
  while (std::getline(dirs, d, ':'))
    for (const char* name : {"chromium", "chromium-browser"}) {
      const fs::path p = fs::path(d) / name;
      std::error_code ec;
      if (!d.empty() && fs::is_regular_file(p, ec) &&
          (fs::status(p, ec).permissions() & fs::perms::owner_exec) != fs::perms::none)
        return p.string();
    }
  return "";
}

struct Browsed {
  std::string dom, console;  // the DOM after load; Chromium's console lines
};

Browsed open_in_chromium(const std::string& chromium, const std::string& html_file) {
  const std::string dom = html_file + ".dom", log = html_file + ".log";
  const std::string cmd = "timeout 120 '" + chromium +
                          "' --headless=new --disable-gpu --no-sandbox --enable-logging=stderr "
                          "--v=0 --virtual-time-budget=5000 --dump-dom 'file://" +
                          fs::absolute(html_file).string() + "' > '" + dom + "' 2> '" + log + "'";
  const int rc = std::system(cmd.c_str());
  INFO(cmd);
  REQUIRE(rc == 0);
  Browsed b{test::file_contents(dom), ""};
  std::stringstream lines(test::file_contents(log));
  for (std::string l; std::getline(lines, l);)
    if (l.find(":CONSOLE") != std::string::npos) b.console += l + "\n";
  return b;
}

}  // namespace

TEST_CASE("report page in headless Chromium: every picture decodes, no console message",
          "[report][browser]") {
  const std::string chromium = find_chromium();
  if (chromium.empty()) {
    WARN("chromium / chromium-browser not on PATH: the report page was not opened in a browser "
         "(scripts/setup.sh installs it with SGNLF_SETUP_BROWSER=1)");
    return;
  }
  const std::string dir = test::temp_dir("report_browser");
  test::write_run_fixture(dir);
  const std::string page = report::write_report(dir);
  const size_t n = test::img_sources(test::file_contents(page)).size();
  REQUIRE(n == 4);
  const Browsed b = open_in_chromium(chromium, page);
  INFO(b.console);
  CHECK(b.console.empty());
  const std::string marker = "data-images=\"" + std::to_string(n) + "/" + std::to_string(n) + "\"";
  CHECK(b.dom.find(marker) != std::string::npos);
  CHECK(b.dom.find("pictures decoded: 4 of 4") != std::string::npos);

  // The check can fail: a picture that does not decode and one the CSP blocks.
  const std::string bad = dir + "/bad.html";
  test::write_text(bad, report::html_page(
                            "bad", "<img src=\"data:image/png;base64,AAAA\" alt=\"broken\">"
                                   "<img src=\"https://example.invalid/x.png\" alt=\"remote\">"));
  const Browsed c = open_in_chromium(chromium, bad);
  CHECK(c.dom.find("data-images=\"0/2\"") != std::string::npos);
  CHECK(c.console.find("picture 0 (broken) did not load") != std::string::npos);
  CHECK(c.console.find("Content Security Policy") != std::string::npos);
}
