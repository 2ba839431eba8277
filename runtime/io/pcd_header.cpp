#include "io/pcd_header.hpp"

#include <charconv>
#include <cmath>
#include <map>

#include "core/error.hpp"
#include "io/scan_io.hpp"

namespace sgnlf::io::detail {
namespace {

constexpr size_t kMaxFields = 4096;      // far above any real PCD (PCL's largest has ~ 40)
constexpr size_t kMaxCount = size_t(1) << 20;

struct KeyLine {
  std::vector<std::string_view> values;
  size_t line = 0, offset = 0;
};

[[noreturn]] void fail(const std::string& path, size_t line, size_t offset, const std::string& what) {
  throw IoError(path + ": header line " + std::to_string(line) + " (byte offset " + std::to_string(offset) +
                "): " + what);
}

bool to_u64(std::string_view s, uint64_t& v) {
  auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

}  // namespace

PcdHeader parse_pcd_header(const std::string& path, const char* bytes, size_t size) {
  static const char* kKeys[] = {"VERSION", "FIELDS", "COLUMNS", "SIZE", "TYPE", "COUNT",
                                "WIDTH", "HEIGHT", "VIEWPOINT", "POINTS", "DATA"};
  std::map<std::string, KeyLine> keys;
  LineCursor cur(bytes, size);
  std::string_view line;
  bool data_seen = false;
  while (!data_seen && cur.next(line)) {
    const auto tok = split_ws(line);
    if (tok.empty() || tok[0][0] == '#') continue;
    const std::string key(tok[0]);
    bool known = false;
    for (const char* k : kKeys) known = known || key == k;
    if (!known) fail(path, cur.line_number(), cur.line_offset(), "unknown key '" + key.substr(0, 40) + "'");
    const std::string canon = key == "COLUMNS" ? "FIELDS" : key;  // v0.5 name of FIELDS
    if (keys.count(canon)) fail(path, cur.line_number(), cur.line_offset(), key + " given twice");
    if (tok.size() < 2) fail(path, cur.line_number(), cur.line_offset(), key + " without a value");
    if (tok.size() - 1 > kMaxFields) fail(path, cur.line_number(), cur.line_offset(), key + " has more than " + std::to_string(kMaxFields) + " values");
    keys[canon] = {std::vector<std::string_view>(tok.begin() + 1, tok.end()), cur.line_number(), cur.line_offset()};
    data_seen = canon == "DATA";
  }
  if (!data_seen)
    throw IoError(path + ": byte offset " + std::to_string(size) + ": header without a DATA line (not a PCD file?)");
  PcdHeader h;
  h.data_offset = cur.offset();
  h.data_line = cur.line_number();
  const KeyLine& data = keys["DATA"];
  if (data.values.size() != 1) fail(path, data.line, data.offset, "DATA takes one value");
  if (data.values[0] == "ascii") h.data = PcdData::kAscii;
  else if (data.values[0] == "binary") h.data = PcdData::kBinary;
  else if (data.values[0] == "binary_compressed") h.data = PcdData::kBinaryCompressed;
  else fail(path, data.line, data.offset, "DATA '" + std::string(data.values[0].substr(0, 40)) + "' is not ascii, binary or binary_compressed");

  for (const char* k : {"FIELDS", "SIZE", "TYPE"})
    if (!keys.count(k)) fail(path, data.line, data.offset, std::string("no ") + k + " line before DATA");
  const KeyLine& fl = keys["FIELDS"];
  const size_t nf = fl.values.size();
  for (const char* k : {"SIZE", "TYPE", "COUNT"}) {
    if (!keys.count(k)) continue;
    const KeyLine& kl = keys[k];
    if (kl.values.size() != nf)
      fail(path, kl.line, kl.offset, std::string(k) + " has " + std::to_string(kl.values.size()) + " values for " +
                                         std::to_string(nf) + " FIELDS");
  }
  const KeyLine& sl = keys["SIZE"];
  const KeyLine& tl = keys["TYPE"];
  uint64_t record = 0, values = 0;
  for (size_t f = 0; f < nf; ++f) {
    PcdField fd;
    fd.name = std::string(fl.values[f]);
    uint64_t sz = 0, cnt = 1;
    if (!to_u64(sl.values[f], sz)) fail(path, sl.line, sl.offset, "SIZE '" + std::string(sl.values[f].substr(0, 20)) + "' of field '" + fd.name + "' is not a count");
    if (tl.values[f].size() != 1 || !pcd_scalar_type(tl.values[f][0], long(std::min<uint64_t>(sz, 16)), fd.type))
      fail(path, tl.line, tl.offset, "field '" + fd.name + "': SIZE " + std::to_string(sz) + " does not fit TYPE '" +
                                         std::string(tl.values[f].substr(0, 20)) + "' (F takes 4 or 8; I and U 1, 2, 4 or 8)");
    if (keys.count("COUNT")) {
      const KeyLine& cl = keys["COUNT"];
      if (!to_u64(cl.values[f], cnt) || cnt == 0 || cnt > kMaxCount)
        fail(path, cl.line, cl.offset, "COUNT '" + std::string(cl.values[f].substr(0, 20)) + "' of field '" + fd.name + "' is not in 1.." + std::to_string(kMaxCount));
    }
    fd.size = size_t(sz);
    fd.count = size_t(cnt);
    fd.offset = size_t(record);
    fd.value_index = size_t(values);
    record += sz * cnt;
    values += cnt;
    h.fields.push_back(std::move(fd));
  }
  if (record > kMaxScanBytes) fail(path, sl.line, sl.offset, "a point of " + std::to_string(record) + " bytes");
  h.record_size = size_t(record);
  h.values_per_point = size_t(values);

  std::vector<std::string> names;
  for (const auto& f : h.fields) names.push_back(f.name);
  std::string err;
  if (!assign_roles(names, h.field_of_role, err)) fail(path, fl.line, fl.offset, err);
  for (size_t r = 0; r < kFieldRoles; ++r) {
    const int f = h.field_of_role[r];
    if (f < 0 && r < 3) fail(path, fl.line, fl.offset, std::string("no field ") + role_name(FieldRole(r)) + " (x, y and z are required)");
    if (f >= 0 && h.fields[size_t(f)].count != 1)
      fail(path, keys["COUNT"].line, keys["COUNT"].offset, "field '" + h.fields[size_t(f)].name + "' has COUNT " +
                                                               std::to_string(h.fields[size_t(f)].count) + "; it must be 1");
  }

  auto number = [&](const char* k, uint64_t& v) {
    const KeyLine& kl = keys[k];
    if (kl.values.size() != 1 || !to_u64(kl.values[0], v))
      fail(path, kl.line, kl.offset, std::string(k) + " '" + std::string(kl.values[0].substr(0, 20)) + "' is not one count");
  };
  const bool has_w = keys.count("WIDTH"), has_h = keys.count("HEIGHT"), has_p = keys.count("POINTS");
  if (has_w) number("WIDTH", h.width);
  if (has_h) number("HEIGHT", h.height);
  if (has_p) number("POINTS", h.points);
  if (!has_w && !has_p) fail(path, data.line, data.offset, "neither WIDTH nor POINTS before DATA");
  if (!has_w) h.width = h.points / (h.height ? h.height : 1);
  const bool overflow = h.height != 0 && h.width > UINT64_MAX / h.height;
  if (!has_p) h.points = overflow ? 0 : h.width * h.height;
  if (overflow || h.width * h.height != h.points) {
    const KeyLine& kl = keys[has_p ? "POINTS" : "WIDTH"];
    fail(path, kl.line, kl.offset, "POINTS " + std::to_string(h.points) + " is not WIDTH " + std::to_string(h.width) +
                                       " x HEIGHT " + std::to_string(h.height));
  }
  if (keys.count("VIEWPOINT")) {
    const KeyLine& vl = keys["VIEWPOINT"];
    bool ok = vl.values.size() == 7;
    for (size_t k = 0; ok && k < 7; ++k) {
      double v = 0;
      ok = parse_scalar(vl.values[k], ScalarType::kF64, v) && std::isfinite(v);
    }
    if (!ok) fail(path, vl.line, vl.offset, "VIEWPOINT needs 7 finite numbers (tx ty tz qw qx qy qz)");
  }
  if (h.points == 0) fail(path, data.line, data.offset, "empty scan (POINTS 0)");
  return h;
}

}  // namespace sgnlf::io::detail
