// write_pose_graph_svg (see pose_graph_svg.hpp).
#include "io/pose_graph_svg.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/config.hpp"
#include "core/error.hpp"

namespace sgnlf::io {
namespace {

std::string xml_escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '&') o += "&amp;";
    else if (c == '<') o += "&lt;";
    else if (c == '>') o += "&gt;";
    else if (c == '"') o += "&quot;";
    else o += c;
  }
  return o;
}

}  // namespace

void write_pose_graph_svg(const std::string& path, const std::string& title,
                          const std::vector<Pose>& T, const std::vector<SvgGraphEdge>& edges,
                          const std::vector<Pose>& reference) {
  require(!T.empty(), path + ": no poses to draw");
  require(reference.empty() || reference.size() == T.size(),
          path + ": reference trajectory has " + std::to_string(reference.size()) +
              " poses for " + std::to_string(T.size()));
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const auto* traj : {&T, &reference})
    for (size_t k = 0; k < traj->size(); ++k) {
      const Vec3 p = (*traj)[k].translation();
      require(p.allFinite(), path + ": pose " + std::to_string(k) + " is not finite");
      x0 = std::min(x0, p.x()), x1 = std::max(x1, p.x());
      y0 = std::min(y0, p.y()), y1 = std::max(y1, p.y());
    }
  double w_max = 0.0;
  size_t n_seq = 0, n_non = 0;
  for (size_t k = 0; k < edges.size(); ++k) {
    const auto& e = edges[k];
    require(e.i >= 0 && e.j >= 0 && size_t(e.i) < T.size() && size_t(e.j) < T.size(),
            path + ": edge " + std::to_string(k) + " (" + std::to_string(e.i) + ", " +
                std::to_string(e.j) + ") is outside the " + std::to_string(T.size()) + " frames");
    require(std::isfinite(e.weight) && e.weight >= 0.0,
            path + ": edge " + std::to_string(k) + " has weight " + std::to_string(e.weight));
    w_max = std::max(w_max, e.weight);
    (e.sequential ? n_seq : n_non) += 1;
  }
  const double W = 800, H = 640, margin = 40, legend = 96;
  const double span = std::max({x1 - x0, y1 - y0, 1.0});
  const double s = std::min((W - 2 * margin) / std::max(x1 - x0, span * 0.05),
                            (H - 2 * margin - legend) / std::max(y1 - y0, span * 0.05));
  const double cx = (x0 + x1) / 2, cy = (y0 + y1) / 2;
  auto px = [&](const Vec3& p) { return W / 2 + (p.x() - cx) * s; };
  auto py = [&](const Vec3& p) { return legend + (H - legend) / 2 - (p.y() - cy) * s; };
  std::ostringstream o;
  char buf[1024];
  o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H
    << "\" font-family=\"sans-serif\" font-size=\"13\">\n"
    << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    << "<text x=\"10\" y=\"18\" font-weight=\"bold\">" << xml_escape(title) << "</text>\n";
  auto polyline = [&](const std::vector<Pose>& traj, const char* color, double width) {
    o << "<polyline fill=\"none\" stroke=\"" << color << "\" stroke-width=\"" << width
      << "\" points=\"";
    for (const auto& P : traj) {
      std::snprintf(buf, sizeof buf, "%.1f,%.1f ", px(P.translation()), py(P.translation()));
      o << buf;
    }
    o << "\"/>\n";
  };
  if (!reference.empty()) polyline(reference, "#bbbbbb", 3.0);
  polyline(T, "#333333", 1.0);
  // Edges: light ones first so that the strong ones are drawn on top.
  std::vector<size_t> order(edges.size());
  for (size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return edges[a].weight < edges[b].weight; });
  for (size_t k : order) {
    const auto& e = edges[k];
    const double rel = w_max > 0 ? e.weight / w_max : 0.0;
    const Vec3 p = T[size_t(e.i)].translation(), q = T[size_t(e.j)].translation();
    std::snprintf(buf, sizeof buf,
                  "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" "
                  "stroke-width=\"%.2f\" stroke-opacity=\"%.3f\"><title>(%d, %d) weight %.4g"
                  "</title></line>\n",
                  px(p), py(p), px(q), py(q), e.sequential ? "#1f77b4" : "#d62728",
                  0.6 + 2.4 * rel, 0.1 + 0.9 * rel, e.i, e.j, e.weight);
    o << buf;
  }
  for (size_t k = 0; k < T.size(); ++k) {
    const Vec3 p = T[k].translation();
    std::snprintf(buf, sizeof buf, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"%.1f\" fill=\"#333\"/>\n",
                  px(p), py(p), k == 0 ? 4.0 : 2.0);
    o << buf;
    if (k % 5 == 0) {
      std::snprintf(buf, sizeof buf,
                    "<text x=\"%.1f\" y=\"%.1f\" font-size=\"10\" fill=\"#333\">%zu</text>\n",
                    px(p) + 4, py(p) - 4, k);
      o << buf;
    }
  }
  std::snprintf(buf, sizeof buf,
                "<line x1=\"12\" y1=\"36\" x2=\"40\" y2=\"36\" stroke=\"#1f77b4\" "
                "stroke-width=\"3\"/><text x=\"48\" y=\"40\">sequential edges (%zu)</text>\n"
                "<line x1=\"12\" y1=\"56\" x2=\"40\" y2=\"56\" stroke=\"#d62728\" "
                "stroke-width=\"3\"/><text x=\"48\" y=\"60\">non-adjacent edges (%zu)</text>\n"
                "<text x=\"12\" y=\"80\" fill=\"#555\">opacity and width: weight / largest "
                "weight (%.3g)%s</text>\n",
                n_seq, n_non, w_max, reference.empty() ? "" : "; grey: reference trajectory");
  o << buf;
  const double target = (W - 2 * margin) / s / 5;
  const double p10 = std::pow(10.0, std::floor(std::log10(target)));
  const double len = target >= 5 * p10 ? 5 * p10 : target >= 2 * p10 ? 2 * p10 : p10;
  std::snprintf(buf, sizeof buf,
                "<line x1=\"%.0f\" y1=\"%.0f\" x2=\"%.1f\" y2=\"%.0f\" stroke=\"black\" "
                "stroke-width=\"2\"/>\n<text x=\"%.0f\" y=\"%.0f\">%g m</text>\n",
                W - margin - len * s, H - 15, W - margin, H - 15, W - margin - len * s, H - 22,
                len);
  o << buf << "</svg>\n";
  write_text_file(path, o.str());
}

}  // namespace sgnlf::io
