// Host reference implementations of the U-Net layer kernels (max pool, bilinear ×2 upsampling,
// channel copy, sigmoid + BCE, box mask), for tests only (the runtime never calls them). Plain
// loops in the order the formulas read, double accumulation; the upsampling backward is written
// as the scatter of the forward's weights (the kernel gathers), so the two are independent.
#pragma once
#include <array>
#include <vector>

#include "conv/avg_pool.hpp"
#include "conv/box_mask.hpp"
#include "conv/channel_copy.hpp"
#include "conv/upsample.hpp"

namespace sgnlf::test::ref {

// Output channels c.. keep `out_init`'s values.
std::vector<float> maxpool2_fwd(const conv::PoolShape& s, const std::vector<float>& in,
                                std::vector<float> out_init);
std::vector<float> maxpool2_bwd(const conv::PoolShape& s, const std::vector<float>& in,
                                const std::vector<float>& d_out, std::vector<float> d_in_init,
                                bool accumulate);

std::vector<float> upsample2_fwd(const conv::UpsampleShape& s, const std::vector<float>& in,
                                 std::vector<float> out_init);
std::vector<float> upsample2_bwd(const conv::UpsampleShape& s, const std::vector<float>& d_out,
                                 std::vector<float> d_in_init, bool accumulate);

std::vector<float> copy_channels(const conv::ChannelCopyShape& s, const std::vector<float>& src,
                                 std::vector<float> dst, bool accumulate);

// Mean BCE of σ(logits[i·cs]) against target[i]; fills d_logits (count × cs, padding 0).
double bce_with_logits(const std::vector<float>& logits, int count, int cs,
                       const std::vector<float>& target, std::vector<float>& d_logits);
std::vector<float> sigmoid(const std::vector<float>& logits, int count, int cs);

// boxes: (y0, x0, y1, x1) half-open.
std::vector<float> box_mask(const conv::BoxMaskShape& s, const std::vector<float>& scale,
                            const std::vector<std::array<int, 4>>& boxes,
                            const std::vector<float>& in, std::vector<float> out_init);

}  // namespace sgnlf::test::ref
