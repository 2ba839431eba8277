#include "report/html.hpp"

#include "core/config.hpp"
#include "io/scan_io.hpp"
#include "report/base64.hpp"

namespace sgnlf::report {

std::string escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string data_uri(const std::string& mime, std::string_view bytes) {
  return "data:" + mime + ";base64," + base64_encode(bytes);
}

std::string embedded_img(const std::string& path, const std::string& mime, const std::string& alt) {
  return "<img src=\"" + data_uri(mime, read_bytes(path)) + "\" alt=\"" + escape(alt) + "\">";
}

std::string read_bytes(const std::string& path) {
  const std::vector<char> b = io::read_file_bytes(path);
  return std::string(b.begin(), b.end());
}

std::string html_table(const std::vector<std::string>& header,
                       const std::vector<std::vector<std::string>>& rows,
                       const std::string& css_class) {
  std::string o = css_class.empty() ? "<table>" : "<table class=\"" + escape(css_class) + "\">";
  bool any_header = false;
  for (const auto& h : header) any_header |= !h.empty();
  if (any_header) {
    o += "<thead><tr>";
    for (const auto& h : header) o += "<th>" + h + "</th>";
    o += "</tr></thead>";
  }
  o += "<tbody>\n";
  for (const auto& r : rows) {
    o += "<tr>";
    for (const auto& c : r) o += "<td>" + c + "</td>";
    o += "</tr>\n";
  }
  return o + "</tbody></table>\n";
}

std::string json_details(const std::string& summary, const Json& value) {
  return "<details><summary>" + escape(summary) + "</summary><pre>" + escape(value.dump(2, ' ', false, Json::error_handler_t::replace)) +
         "</pre></details>\n";
}

std::string anchor_id(std::string_view text) {
  std::string id;
  for (const char c : text) {
    const char l = (c >= 'A' && c <= 'Z') ? char(c - 'A' + 'a') : c;
    const bool keep = (l >= 'a' && l <= 'z') || (l >= '0' && l <= '9');
    if (keep) id += l;
    else if (!id.empty() && id.back() != '-') id += '-';
  }
  while (!id.empty() && id.back() == '-') id.pop_back();
  return id.empty() ? "x" : id;
}

}  // namespace sgnlf::report
