// The report's building blocks: base64 against RFC 4648's test vectors, HTML escaping, anchor
// ids and the SVG chart's ticks and empty cases.
#include <catch2/catch.hpp>

#include "core/error.hpp"
#include "report/base64.hpp"
#include "report/html.hpp"
#include "report/svg_chart.hpp"

using namespace sgnlf;
using namespace sgnlf::report;

TEST_CASE("base64: RFC 4648 §10 vectors, both ways", "[report]") {
  const std::pair<const char*, const char*> v[] = {{"", ""},         {"f", "Zg=="},
                                                   {"fo", "Zm8="},   {"foo", "Zm9v"},
                                                   {"foob", "Zm9vYg=="}, {"fooba", "Zm9vYmE="},
                                                   {"foobar", "Zm9vYmFy"}};
  for (const auto& [plain, coded] : v) {
    CHECK(base64_encode(plain) == coded);
    CHECK(base64_decode(coded) == plain);
  }
}

TEST_CASE("base64: every byte value round-trips; bad text is refused", "[report]") {
  std::string all;
  for (int i = 0; i < 256; ++i) all += char(i);
  for (size_t n : {size_t(0), size_t(1), size_t(2), size_t(3), size_t(255), size_t(256)}) {
    const std::string enc = base64_encode(all.substr(0, n));
    CHECK(enc.size() == (n + 2) / 3 * 4);
    CHECK(base64_decode(enc) == all.substr(0, n));
  }
  CHECK(base64_encode("\xff\xfe\xfd") == "//79");
  CHECK_THROWS_AS(base64_decode("Zm9"), Error);     // length
  CHECK_THROWS_AS(base64_decode("Zm9v!A=="), Error);  // alphabet
  CHECK_THROWS_AS(base64_decode("Zg==Zg=="), Error);  // padding inside
  CHECK_THROWS_AS(base64_decode("Z=g="), Error);      // padding before data
}

TEST_CASE("escape: the five characters that matter in HTML text and attributes", "[report]") {
  CHECK(escape("a<b>&\"c'") == "a&lt;b&gt;&amp;&quot;c&#39;");
  CHECK(escape("plain, ü ≥") == "plain, ü ≥");
  CHECK(anchor_id("run-sg-nlf/KITTI360 low_a") == "run-sg-nlf-kitti360-low-a");
  CHECK(anchor_id("<>") == "x");
  CHECK(html_table({"", ""}, {{"a", "b"}}).find("<thead>") == std::string::npos);
  CHECK(html_table({"h", ""}, {{"a", "b"}}).find("<th>h</th>") != std::string::npos);
}

TEST_CASE("svg_chart: 1-2-5 ticks, log axes, escaped text, no data", "[report]") {
  const auto t = nice_ticks(0, 1, 5);
  REQUIRE(t.size() == 6);
  CHECK(t[1] == Approx(0.2));
  CHECK(nice_ticks(3, 97, 5) == std::vector<double>{20, 40, 60, 80});
  ChartSeries s{"a<b", "#123456", {1, 2, 3, 4}, {10, 0, 1000, NAN}};
  const std::string svg = svg_chart({s}, {"T & U", "x", "y", true});
  CHECK(svg.find("<title>T &amp; U</title>") != std::string::npos);
  CHECK(svg.find("a&lt;b") != std::string::npos);
  // y = 0 (log axis) and NaN break the line: one point, then one point → two polylines.
  CHECK(svg.find(">1000</text>") != std::string::npos);
  size_t lines = 0;
  for (size_t p = svg.find("<polyline"); p != std::string::npos; p = svg.find("<polyline", p + 1)) ++lines;
  CHECK(lines == 2);
  CHECK(svg_chart({}, {"empty", "", ""}).find("no data") != std::string::npos);
  CHECK(svg_chart({{"n", "", {1}, {NAN}}}, {"nan", "", ""}).find("no data") != std::string::npos);
}
