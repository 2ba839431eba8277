// write_trajectory_svg (see trajectory_svg.hpp).
#include "io/trajectory_svg.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "core/error.hpp"

namespace sgnlf::io {

void write_trajectory_svg(const std::string& path, const std::string& title,
                          const std::vector<SvgTrajectory>& trajs,
                          const std::vector<std::pair<int, int>>& links) {
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const auto& t : trajs)
    for (size_t k = 0; k < t.poses.size(); ++k) {
      const Vec3 p = t.poses[k].translation();
      if (!p.allFinite())
        throw Error(path + ": trajectory '" + t.name + "' pose " + std::to_string(k) + " is not finite");
      x0 = std::min(x0, p.x()), x1 = std::max(x1, p.x());
      y0 = std::min(y0, p.y()), y1 = std::max(y1, p.y());
    }
  if (x0 > x1) throw Error(path + ": no poses to draw");
  const double W = 800, H = 600, margin = 40, legend = 24.0 * double(trajs.size()) + 30;
  const double span = std::max({x1 - x0, y1 - y0, 1.0});
  const double s = std::min((W - 2 * margin) / std::max(x1 - x0, 1e-9 + span * 0.05),
                            (H - 2 * margin - legend) / std::max(y1 - y0, 1e-9 + span * 0.05));
  const double cx = (x0 + x1) / 2, cy = (y0 + y1) / 2;
  auto px = [&](const Vec3& p) { return W / 2 + (p.x() - cx) * s; };
  auto py = [&](const Vec3& p) { return legend + (H - legend) / 2 - (p.y() - cy) * s; };
  std::ostringstream o;
  char buf[256];
  o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H
    << "\" font-family=\"sans-serif\" font-size=\"13\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  o << "<text x=\"10\" y=\"18\" font-weight=\"bold\">" << title << "</text>\n";
  for (const auto& [a, b] : links) {
    if (a < 0 || b < 0 || size_t(a) >= trajs.size() || size_t(b) >= trajs.size() ||
        trajs[size_t(a)].poses.size() != trajs[size_t(b)].poses.size())
      throw Error(path + ": bad link between trajectories " + std::to_string(a) + " and " + std::to_string(b));
    for (size_t k = 0; k < trajs[size_t(a)].poses.size(); ++k) {
      const Vec3 p = trajs[size_t(a)].poses[k].translation(), q = trajs[size_t(b)].poses[k].translation();
      std::snprintf(buf, sizeof buf, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#bbb\" stroke-width=\"0.7\"/>\n",
                    px(p), py(p), px(q), py(q));
      o << buf;
    }
  }
  for (size_t t = 0; t < trajs.size(); ++t) {
    const auto& tr = trajs[t];
    o << "<polyline fill=\"none\" stroke=\"" << tr.color << "\" stroke-width=\"1.5\" points=\"";
    for (const auto& T : tr.poses) {
      std::snprintf(buf, sizeof buf, "%.1f,%.1f ", px(T.translation()), py(T.translation()));
      o << buf;
    }
    o << "\"/>\n";
    for (size_t k = 0; k < tr.poses.size(); ++k) {
      const Vec3 p = tr.poses[k].translation();
      std::snprintf(buf, sizeof buf, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"%.1f\" fill=\"%s\"/>\n", px(p),
                    py(p), k == 0 ? 4.5 : 2.2, tr.color.c_str());
      o << buf;
    }
    const double ly = 40 + 22.0 * double(t);
    std::snprintf(buf, sizeof buf, "<line x1=\"12\" y1=\"%.0f\" x2=\"40\" y2=\"%.0f\" stroke=\"%s\" stroke-width=\"3\"/>\n",
                  ly - 4, ly - 4, tr.color.c_str());
    o << buf << "<text x=\"48\" y=\"" << ly << "\">" << tr.name << "</text>\n";
  }
  // Scale bar: a round length near a fifth of the picture.
  const double target = (W - 2 * margin) / s / 5;
  const double p10 = std::pow(10.0, std::floor(std::log10(target)));
  const double len = target >= 5 * p10 ? 5 * p10 : target >= 2 * p10 ? 2 * p10 : p10;
  std::snprintf(buf, sizeof buf, "<line x1=\"%.0f\" y1=\"%.0f\" x2=\"%.1f\" y2=\"%.0f\" stroke=\"black\" stroke-width=\"2\"/>\n"
                "<text x=\"%.0f\" y=\"%.0f\">%g m</text>\n", W - margin - len * s, H - 15, W - margin, H - 15,
                W - margin - len * s, H - 22, len);
  o << buf << "</svg>\n";
  std::ofstream f(path);
  if (!f) throw IoError(path + ": cannot open for writing");
  f << o.str();
  if (!f) throw IoError(path + ": write failed");
}

}  // namespace sgnlf::io
