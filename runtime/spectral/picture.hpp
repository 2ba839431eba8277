// PNG pictures of eigenfunctions on a surface: each function drawn over the shape's chart
// (equirectangular for the sphere) with a diverging blue–white–red colormap scaled by its
// largest |value|, functions tiled in a grid.
#pragma once
#include <string>
#include <vector>

namespace sgnlf::spectral {

// An RGB8 image.
struct Image {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;
};

// values: n_funcs maps of tile_w × tile_h (row-major, map f at f·tile_w·tile_h); `cols` per row,
// with a 4-pixel white gap.
Image tile_maps(const std::vector<float>& values, int n_funcs, int tile_w, int tile_h, int cols);
void write_png(const std::string& path, const Image& img);  // throws IoError

}  // namespace sgnlf::spectral
