// marked_depth_picture (see marked_depth_picture.hpp).
#include "io/marked_depth_picture.hpp"

#include <algorithm>

#include "core/error.hpp"

namespace sgnlf::io {

RgbImage marked_depth_picture(const std::vector<DepthPanel>& panels, const RangePictureOptions& opt) {
  require(!panels.empty(), "marked_depth_picture: no panels");
  for (size_t k = 0; k < panels.size(); ++k) {
    const RangeImage* img = panels[k].image;
    require(img != nullptr, "marked_depth_picture: panel " + std::to_string(k) + " has no image");
    require(img->height == panels[0].image->height && img->width == panels[0].image->width &&
                img->range.size() == img->size(),
            "marked_depth_picture: panel " + std::to_string(k) + " is " +
                std::to_string(img->height) + "x" + std::to_string(img->width) + ", panel 0 " +
                std::to_string(panels[0].image->height) + "x" + std::to_string(panels[0].image->width));
    require(panels[k].marks.empty() || panels[k].marks.size() == img->size(),
            "marked_depth_picture: panel " + std::to_string(k) + " has " +
                std::to_string(panels[k].marks.size()) + " marks for " +
                std::to_string(img->size()) + " pixels");
  }
  const int rep = std::max(1, opt.row_repeat), h = panels[0].image->height;
  const int panel_rows = h * rep;
  RgbImage out;
  out.width = panels[0].image->width;
  out.height = int(panels.size()) * panel_rows + int(panels.size() - 1) * opt.gap;
  out.rgb.assign(size_t(out.height) * out.width * 3, 0);
  for (size_t k = 0; k < panels.size(); ++k) {
    const RangeImage& img = *panels[k].image;
    const int y0 = int(k) * (panel_rows + opt.gap);
    for (int r = 0; r < img.height; ++r)
      for (int c = 0; c < img.width; ++c) {
        const size_t i = img.idx(r, c);
        const uint8_t mark = panels[k].marks.empty() ? uint8_t(kMarkNone) : panels[k].marks[i];
        std::array<uint8_t, 3> colour = {0, 0, 0};
        if (mark == kMarkFalseReturn) colour = kFalseReturnColour;
        else if (mark == kMarkMissedReturn) colour = kMissedReturnColour;
        else if (img.range[i] > 0.f) colour = depth_colour(double(img.range[i]), opt);
        for (int j = 0; j < rep; ++j)
          std::copy(colour.begin(), colour.end(),
                    &out.rgb[(size_t(y0 + r * rep + j) * out.width + c) * 3]);
      }
  }
  return out;
}

}  // namespace sgnlf::io
