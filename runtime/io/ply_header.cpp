#include "io/ply_header.hpp"

#include <charconv>

#include "core/error.hpp"

namespace sgnlf::io::detail {
namespace {

constexpr size_t kMaxProperties = 4096;

[[noreturn]] void fail(const std::string& path, size_t line, size_t offset, const std::string& what) {
  throw IoError(path + ": header line " + std::to_string(line) + " (byte offset " + std::to_string(offset) +
                "): " + what);
}

std::string clip(std::string_view s) { return std::string(s.substr(0, 40)); }

}  // namespace

PlyHeader parse_ply_header(const std::string& path, const char* bytes, size_t size) {
  LineCursor cur(bytes, size);
  std::string_view line;
  if (!cur.next(line) || line != "ply")
    throw IoError(path + ": byte offset 0: not a PLY file (the first line is not 'ply')");
  PlyHeader h;
  bool format_seen = false, end_seen = false;
  while (!end_seen && cur.next(line)) {
    const size_t ln = cur.line_number(), off = cur.line_offset();
    const auto tok = split_ws(line);
    if (tok.empty()) continue;
    const std::string_view key = tok[0];
    if (key == "comment" || key == "obj_info") continue;
    if (key == "end_header") {
      end_seen = true;
    } else if (key == "format") {
      if (format_seen) fail(path, ln, off, "format given twice");
      if (tok.size() != 3 || tok[2] != "1.0") fail(path, ln, off, "expected 'format <encoding> 1.0'");
      if (tok[1] == "ascii") h.format = PlyFormat::kAscii;
      else if (tok[1] == "binary_little_endian") h.format = PlyFormat::kBinaryLittleEndian;
      else if (tok[1] == "binary_big_endian") h.format = PlyFormat::kBinaryBigEndian;
      else fail(path, ln, off, "format '" + clip(tok[1]) + "' is not ascii, binary_little_endian or binary_big_endian");
      format_seen = true;
    } else if (key == "element") {
      PlyElement e;
      const auto& c = tok.size() == 3 ? tok[2] : std::string_view();
      auto r = std::from_chars(c.data(), c.data() + c.size(), e.count);
      if (tok.size() != 3 || r.ec != std::errc() || r.ptr != c.data() + c.size())
        fail(path, ln, off, "expected 'element <name> <count>'");
      e.name = std::string(tok[1]);
      e.line = ln;
      e.line_offset = off;
      if (e.name == "vertex") {
        for (const auto& other : h.elements)
          if (other.name == "vertex") fail(path, ln, off, "a second vertex element");
        h.vertex = h.elements.size();
      }
      h.elements.push_back(std::move(e));
    } else if (key == "property") {
      if (h.elements.empty()) fail(path, ln, off, "property before any element");
      PlyElement& e = h.elements.back();
      if (e.props.size() == kMaxProperties) fail(path, ln, off, "more than " + std::to_string(kMaxProperties) + " properties");
      PlyProperty p;
      if (tok.size() == 5 && tok[1] == "list") {
        p.is_list = true;
        if (!ply_scalar_type(tok[2], p.count_type) || !scalar_is_integer(p.count_type))
          fail(path, ln, off, "list count type '" + clip(tok[2]) + "' is not an integer type");
        if (!ply_scalar_type(tok[3], p.type)) fail(path, ln, off, "unknown list item type '" + clip(tok[3]) + "'");
        p.name = std::string(tok[4]);
        e.has_list = true;
      } else if (tok.size() == 3) {
        if (!ply_scalar_type(tok[1], p.type)) fail(path, ln, off, "unknown property type '" + clip(tok[1]) + "'");
        p.name = std::string(tok[2]);
        e.record_size += scalar_size(p.type);
      } else {
        fail(path, ln, off, "expected 'property <type> <name>' or 'property list <count type> <item type> <name>'");
      }
      e.props.push_back(std::move(p));
    } else {
      fail(path, ln, off, "unknown keyword '" + clip(key) + "'");
    }
  }
  if (!end_seen) throw IoError(path + ": byte offset " + std::to_string(size) + ": header without end_header");
  if (!format_seen) fail(path, cur.line_number(), cur.line_offset(), "no format line before end_header");
  h.data_offset = cur.offset();
  h.data_line = cur.line_number();
  bool has_vertex = false;
  for (const auto& e : h.elements) has_vertex = has_vertex || e.name == "vertex";
  if (!has_vertex) fail(path, cur.line_number(), cur.line_offset(), "no vertex element");
  const PlyElement& v = h.elements[h.vertex];
  std::vector<std::string> names;
  for (const auto& p : v.props) names.push_back(p.name);
  std::string err;
  if (!assign_roles(names, h.field_of_role, err)) fail(path, v.line, v.line_offset, "element vertex: " + err);
  for (size_t r = 0; r < kFieldRoles; ++r) {
    const int k = h.field_of_role[r];
    if (k < 0 && r < 3) fail(path, v.line, v.line_offset, std::string("element vertex has no property ") + role_name(FieldRole(r)) + " (x, y and z are required)");
    if (k >= 0 && v.props[size_t(k)].is_list) fail(path, v.line, v.line_offset, "vertex property '" + v.props[size_t(k)].name + "' is a list");
  }
  if (v.count == 0) fail(path, v.line, v.line_offset, "empty scan (element vertex 0)");
  return h;
}

}  // namespace sgnlf::io::detail
