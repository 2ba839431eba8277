// HTML building blocks of the report: escaping of every inserted text, data: URIs for embedded
// files, tables whose cells the caller has already escaped, and collapsible JSON blocks.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "core/config_fwd.hpp"

namespace sgnlf::report {

// Escapes & < > " ' so that the text is safe in element content and in quoted attributes.
std::string escape(std::string_view text);

// "data:<mime>;base64,<bytes in base64>".
std::string data_uri(const std::string& mime, std::string_view bytes);

// <img> of the file at `path` as a data: URI with `alt` text (IoError when it cannot be read).
std::string embedded_img(const std::string& path, const std::string& mime, const std::string& alt);

// The whole file as bytes; IoError naming the path when it cannot be read.
std::string read_bytes(const std::string& path);

// A table: `header` and `rows` are HTML fragments (escape text before passing it).
std::string html_table(const std::vector<std::string>& header,
                       const std::vector<std::vector<std::string>>& rows,
                       const std::string& css_class = "");

// <details><summary>summary</summary><pre>JSON, indented</pre></details>.
std::string json_details(const std::string& summary, const Json& value);

// An anchor id made of [a-z0-9-] from any text ("sg-nlf/kitti360-low-a" → "sg-nlf-kitti360-low-a").
std::string anchor_id(std::string_view text);

}  // namespace sgnlf::report
