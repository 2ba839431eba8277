// Progressive spectral-geometric fusion (method.md §4.1): f_hyb = [f_geo, λ·Ψ(x)] per point,
// row-major, width G + K; and its backward. Widths are -D defines (FUSION_G, FUSION_K), so the
// index split is a division by a constant; one work-item per output element, 1-D range.

#define FUSION_W (FUSION_G + FUSION_K)

__kernel void spectral_fusion_fwd(const int n, const float lambda, __global const float* geo,
                                  __global const float* psi, __global float* hyb) {
  const int idx = get_global_id(0);
  if (idx >= n * FUSION_W) return;
  const int i = idx / FUSION_W, c = idx - i * FUSION_W;
  hyb[idx] = c < FUSION_G ? geo[i * FUSION_G + c] : lambda * psi[i * FUSION_K + (c - FUSION_G)];
}

// d_geo (when write_geo) = d_hyb[:, :G]; d_psi = λ · d_hyb[:, G:] (overwritten).
__kernel void spectral_fusion_bwd(const int n, const float lambda, const int write_geo,
                                  __global const float* d_hyb, __global float* d_geo,
                                  __global float* d_psi) {
  const int idx = get_global_id(0);
  if (idx >= n * FUSION_W) return;
  const int i = idx / FUSION_W, c = idx - i * FUSION_W;
  if (c >= FUSION_G) {
    d_psi[i * FUSION_K + (c - FUSION_G)] = lambda * d_hyb[idx];
  } else if (write_geo) {
    d_geo[i * FUSION_G + c] = d_hyb[idx];
  }
}
