#include "report/svg_chart.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "report/html.hpp"

namespace sgnlf::report {
namespace {

constexpr double kLeft = 70, kRight = 16, kTop = 44, kBottom = 42;

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", std::abs(v) < 1e-12 ? 0.0 : v);
  return buf;
}

std::string coord(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v);
  return buf;
}

struct Range {
  double lo = INFINITY, hi = -INFINITY;
  void add(double v) { lo = std::min(lo, v), hi = std::max(hi, v); }
  bool empty() const { return !(lo <= hi); }
  double span() const { return hi - lo; }
  void pad_if_flat() {
    if (span() > 0) return;
    const double d = lo == 0 ? 0.5 : std::abs(lo) * 0.1;
    lo -= d, hi += d;
  }
};

bool usable(double x, double y, bool log_y) {
  return std::isfinite(x) && std::isfinite(y) && (!log_y || y > 0);
}

// Positions (log10) of the ticks of a log axis spanning [lo, hi] in log10: powers of ten, or
// 1-2-5 steps of the values themselves when the axis spans less than a decade.
std::vector<double> log_ticks(double lo, double hi) {
  std::vector<double> t;
  if (hi - lo < 1) {
    for (double v : nice_ticks(std::pow(10.0, lo), std::pow(10.0, hi), 4))
      if (v > 0) t.push_back(std::log10(v));
    return t;
  }
  const int stride = std::max(1, int(std::ceil((hi - lo) / 6)));
  for (int k = int(std::ceil(lo)); k <= int(std::floor(hi)); k += stride) t.push_back(k);
  return t;
}

}  // namespace

std::vector<double> nice_ticks(double lo, double hi, int target) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(hi > lo)) return {lo};
  const double raw = (hi - lo) / std::max(1, target);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double n = raw / mag;
  const double step = (n < 1.5 ? 1 : n < 3 ? 2 : n < 7 ? 5 : 10) * mag;
  std::vector<double> t;
  for (double v = std::ceil(lo / step) * step; v <= hi + step * 1e-9; v += step)
    t.push_back(std::abs(v) < step * 1e-9 ? 0.0 : v);
  return t;
}

std::string svg_chart(const std::vector<ChartSeries>& series, const ChartOptions& opt) {
  const double W = opt.width, H = opt.height;
  const double pw = W - kLeft - kRight, ph = H - kTop - kBottom;
  auto ty = [&](double y) { return opt.log_y ? std::log10(y) : y; };
  Range rx, ry;
  for (const auto& s : series)
    for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i)
      if (usable(s.x[i], s.y[i], opt.log_y)) rx.add(s.x[i]), ry.add(ty(s.y[i]));

  std::string o = "<svg class=\"chart\" width=\"" + num(W) + "\" height=\"" + num(H) +
                  "\" viewBox=\"0 0 " + num(W) + " " + num(H) +
                  "\" role=\"img\" font-family=\"sans-serif\" font-size=\"11\">";
  o += "<title>" + escape(opt.title) + "</title>";
  o += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>";
  o += "<text x=\"8\" y=\"16\" font-weight=\"bold\" font-size=\"13\">" + escape(opt.title) +
       "</text>";
  if (rx.empty()) {
    o += "<text x=\"" + coord(W / 2) + "\" y=\"" + coord(H / 2) +
         "\" text-anchor=\"middle\" fill=\"#888\">no data</text></svg>";
    return o;
  }
  rx.pad_if_flat(), ry.pad_if_flat();
  if (opt.equal_axes) {  // widen the axis with room to spare so that both use one scale
    const double s = std::max(rx.span() / pw, ry.span() / ph);
    const double cx = (rx.lo + rx.hi) / 2, cy = (ry.lo + ry.hi) / 2;
    rx = {cx - s * pw / 2, cx + s * pw / 2};
    ry = {cy - s * ph / 2, cy + s * ph / 2};
  }
  auto px = [&](double x) { return kLeft + (x - rx.lo) / rx.span() * pw; };
  auto py = [&](double y) { return kTop + ph - (y - ry.lo) / ry.span() * ph; };

  // Grid and tick labels.
  for (double t : nice_ticks(rx.lo, rx.hi, 6)) {
    o += "<line x1=\"" + coord(px(t)) + "\" y1=\"" + coord(kTop) + "\" x2=\"" + coord(px(t)) +
         "\" y2=\"" + coord(kTop + ph) + "\" stroke=\"#e4e4e4\"/>";
    o += "<text x=\"" + coord(px(t)) + "\" y=\"" + coord(kTop + ph + 14) +
         "\" text-anchor=\"middle\">" + escape(num(t)) + "</text>";
  }
  for (double t : opt.log_y ? log_ticks(ry.lo, ry.hi) : nice_ticks(ry.lo, ry.hi, 5)) {
    o += "<line x1=\"" + coord(kLeft) + "\" y1=\"" + coord(py(t)) + "\" x2=\"" +
         coord(kLeft + pw) + "\" y2=\"" + coord(py(t)) + "\" stroke=\"#e4e4e4\"/>";
    o += "<text x=\"" + coord(kLeft - 4) + "\" y=\"" + coord(py(t) + 4) +
         "\" text-anchor=\"end\">" + escape(num(opt.log_y ? std::pow(10.0, t) : t)) + "</text>";
  }
  o += "<rect x=\"" + coord(kLeft) + "\" y=\"" + coord(kTop) + "\" width=\"" + coord(pw) +
       "\" height=\"" + coord(ph) + "\" fill=\"none\" stroke=\"#444\"/>";
  o += "<text x=\"" + coord(kLeft + pw / 2) + "\" y=\"" + coord(H - 8) +
       "\" text-anchor=\"middle\">" + escape(opt.x_label) + "</text>";
  o += "<text transform=\"translate(14," + coord(kTop + ph / 2) +
       ") rotate(-90)\" text-anchor=\"middle\">" + escape(opt.y_label) +
       (opt.log_y ? " (log)" : "") + "</text>";

  // Series: a polyline per run of usable points, a legend entry each.
  double lx = kLeft;
  for (const auto& s : series) {
    const std::string colour = escape(s.color.empty() ? "#1f77b4" : s.color);
    std::string pts, dots;
    auto flush = [&] {
      if (!pts.empty())
        o += "<polyline class=\"series\" fill=\"none\" stroke=\"" + colour +
             "\" stroke-width=\"1.5\" points=\"" + pts + "\"/>";
      pts.clear();
    };
    for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!usable(s.x[i], s.y[i], opt.log_y)) {
        flush();
        continue;
      }
      const std::string p = coord(px(s.x[i])) + "," + coord(py(ty(s.y[i])));
      pts += (pts.empty() ? "" : " ") + p;
      if (s.dots)
        dots += "<circle cx=\"" + coord(px(s.x[i])) + "\" cy=\"" + coord(py(ty(s.y[i]))) +
                "\" r=\"2\" fill=\"" + colour + "\"/>";
    }
    flush();
    o += dots;
    o += "<rect x=\"" + coord(lx) + "\" y=\"26\" width=\"12\" height=\"4\" fill=\"" + colour +
         "\"/><text x=\"" + coord(lx + 16) + "\" y=\"32\">" + escape(s.name) + "</text>";
    lx += 28 + 6.5 * double(s.name.size());
  }
  return o + "</svg>\n";
}

}  // namespace sgnlf::report
