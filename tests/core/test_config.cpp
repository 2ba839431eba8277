#include <catch2/catch.hpp>

#include <cstdint>
#include <fstream>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "core/config.hpp"
#include "core/config_fields.hpp"

using namespace sgnlf;

namespace {
struct Cfg {
  int iterations = 10;
  double lr = 0.01;
  bool flag = false;
  std::string name = "x";
};
Cfg parse(const Json& j) {
  Cfg c;
  ConfigReader r(j, "test.json");
  r.get("iterations", c.iterations).get("lr", c.lr).get("flag", c.flag).get("name", c.name);
  r.finish();
  return c;
}
}  // namespace

TEST_CASE("config reader keeps defaults and reads given keys", "[config]") {
  const auto c = parse(Json::parse(R"({"iterations": 5, "name": "y"})"));
  CHECK(c.iterations == 5);
  CHECK(c.lr == 0.01);
  CHECK(c.name == "y");
}

TEST_CASE("unknown keys are rejected by name", "[config]") {
  try {
    parse(Json::parse(R"({"iterations": 5, "itertions": 6})"));
    FAIL("expected ConfigError");
  } catch (const ConfigError& e) {
    CHECK_THAT(e.what(), Catch::Contains("itertions"));
    CHECK_THAT(e.what(), Catch::Contains("test.json"));
  }
  // A misspelling names the key that was meant; a key far from every valid one names none.
  CHECK_THROWS_WITH(parse(Json::parse(R"({"itertions": 6})")),
                    Catch::Contains("'itertions' (did you mean 'iterations'?)"));
  CHECK_THROWS_WITH(parse(Json::parse(R"({"temperature": 6})")),
                    Catch::Contains("'temperature'") && !Catch::Contains("did you mean"));
  CHECK(nearest_key("n_sample", {"n_samples", "n_importance"}) == "n_samples");
  CHECK(nearest_key("lr", {"n_samples", "seed"}).empty());
}

TEST_CASE("wrong types name the key and the value", "[config]") {
  CHECK_THROWS_WITH(parse(Json::parse(R"({"iterations": "many"})")),
                    Catch::Contains("iterations") && Catch::Contains("many"));
  CHECK_THROWS_AS(parse(Json::parse(R"({"iterations": 1.5})")), ConfigError);
  CHECK_THROWS_AS(parse(Json::parse(R"({"flag": 1})")), ConfigError);
  CHECK_THROWS_AS(parse(Json::parse(R"([1, 2])")), ConfigError);
}

TEST_CASE("json files: missing and invalid files name the file and offset", "[config]") {
  CHECK_THROWS_WITH(load_json_file("/nonexistent/cfg.json"), Catch::Contains("/nonexistent/cfg.json"));
  const std::string p = "test_config_bad.json";
  std::ofstream(p) << "{\"a\": 1,,}";
  CHECK_THROWS_WITH(load_json_file(p), Catch::Contains("test_config_bad.json") && Catch::Contains("byte"));
  // A config file the user names: a syntax error is a config error (exit 2), with line and column.
  std::ofstream(p) << "{\n  \"a\": 1,\n  \"b\": ]\n}";
  try {
    load_config_file(p);
    FAIL("expected ConfigError");
  } catch (const ConfigError& e) {
    CHECK_THAT(e.what(), Catch::Contains("test_config_bad.json") && Catch::Contains("line 3") &&
                             Catch::Contains("column 8"));
  }
  CHECK_THROWS_AS(load_config_file("/nonexistent/cfg.json"), ConfigError);
  write_json_file(p, Json{{"a", 1}});
  CHECK(load_json_file(p)["a"] == 1);
  CHECK(load_config_file(p)["a"] == 1);
}

TEST_CASE("integers out of the field's range are refused, not narrowed", "[config]") {
  auto read = [](const Json& j, auto& out) {
    const Json doc{{"v", j}};  // the reader keeps a reference
    ConfigReader r(doc, "range.json");
    r.get("v", out);
  };
  int i = 0;
  CHECK_THROWS_WITH(read(Json(4294967296LL), i), Catch::Contains("'v'") && Catch::Contains("4294967296"));
  CHECK_THROWS_AS(read(Json(-2147483649LL), i), ConfigError);
  CHECK_THROWS_AS(read(Json(18446744073709551615ULL), i), ConfigError);
  read(Json(-2147483648LL), i);
  CHECK(i == std::numeric_limits<int>::min());
  uint32_t u = 0;
  CHECK_THROWS_AS(read(Json(-1), u), ConfigError);
  CHECK_THROWS_AS(read(Json(4294967296LL), u), ConfigError);
  read(Json(4294967295LL), u);
  CHECK(u == 4294967295u);
  uint64_t big = 0;
  read(Json(18446744073709551615ULL), big);
  CHECK(big == std::numeric_limits<uint64_t>::max());
  long long ll = 0;
  CHECK_THROWS_AS(read(Json(18446744073709551615ULL), ll), ConfigError);
  size_t sz = 0;
  CHECK_THROWS_AS(read(Json(1.5), sz), ConfigError);
  read(Json(300), sz);  // a signed JSON integer into an unsigned field
  CHECK(sz == 300);
}

TEST_CASE("lists are read entry by entry as strictly as single values", "[config]") {
  auto read = [](const Json& j, auto& out) {
    const Json doc{{"v", j}};
    ConfigReader r(doc, "list.json");
    r.get("v", out);
  };
  std::vector<int> ints;
  read(Json{1, 2, -3}, ints);
  CHECK(ints == std::vector<int>{1, 2, -3});
  CHECK_THROWS_WITH(read(Json{32, 64.5, 128}, ints), Catch::Contains("'v'") && Catch::Contains("64.5"));
  CHECK_THROWS_AS(read(Json{1, true}, ints), ConfigError);
  CHECK_THROWS_AS(read(Json{1, "2"}, ints), ConfigError);
  CHECK_THROWS_AS(read(Json{4294967296LL}, ints), ConfigError);
  CHECK_THROWS_AS(read(Json(3), ints), ConfigError);
  CHECK(ints == std::vector<int>{1, 2, -3});  // a refused list leaves the field as it was
  std::vector<double> reals;
  read(Json{1, 2.5}, reals);
  CHECK(reals == std::vector<double>{1.0, 2.5});
  std::vector<std::string> names;
  CHECK_THROWS_AS(read(Json{"a", 1}, names), ConfigError);
}

namespace {
enum class Shape { round, square };
constexpr std::pair<Shape, const char*> kShapes[] = {{Shape::round, "round"}, {Shape::square, "square"}};
struct Inner {
  int n = 2;
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("n", s.n, 1, 9);
  }
  static Inner from_json(const Json& j, const std::string& where) {
    Inner c;
    ConfigReader r(j, where);
    config::read_fields_here(r, c);
    r.finish();
    return c;
  }
  Json to_json() const { return config::write_fields(*this); }
};
struct Outer {
  Shape shape = Shape::round;
  Inner inner;
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("shape", s.shape, config::choices(kShapes));
    v.object("inner", s.inner);
  }
};
}  // namespace

TEST_CASE("field lists: an enum is its value's name; a nested config's keys are described",
          "[config]") {
  const Json j{{"shape", "square"}, {"inner", {{"n", 3}}}};
  ConfigReader r(j, "shapes.json");
  Outer o;
  config::read_fields_here(r, o);
  r.finish();
  CHECK(o.shape == Shape::square);
  CHECK(o.inner.n == 3);
  CHECK(config::write_fields(o) == j);
  const Json bad{{"shape", "oval"}};
  ConfigReader rb(bad, "shapes.json");
  CHECK_THROWS_WITH(config::read_fields_here(rb, o),
                    Catch::Contains("shapes.json") && Catch::Contains("'shape'") &&
                        Catch::Contains("oval") && Catch::Contains("round, square"));
  const Json wrong{{"shape", 1}};
  ConfigReader rw(wrong, "shapes.json");
  CHECK_THROWS_WITH(config::read_fields_here(rw, o), Catch::Contains("'shape'"));
  const Json schema = config::describe_fields<Outer>();
  CHECK(schema["shape"]["type"] == "string");
  CHECK(schema["shape"]["default"] == "round");
  CHECK(schema["shape"]["one_of"] == Json{"round", "square"});
  CHECK(schema["inner"]["type"] == "object");
  CHECK(schema["inner"]["fields"]["n"]["max"] == 9);
}
