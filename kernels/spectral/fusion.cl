// Progressive spectral-geometric fusion (method.md §4.1): f_hyb = [f_geo, λ·Ψ(x)] per point,
// row-major, width G + K; and its backward. One work-item per output element.

__kernel void spectral_fusion_fwd(const int n, const int g, const int k, const float lambda,
                                  __global const float* geo, __global const float* psi,
                                  __global float* hyb) {
  const int w = g + k;
  const int idx = get_global_id(0);
  if (idx >= n * w) return;
  const int i = idx / w, c = idx - i * w;
  hyb[idx] = c < g ? geo[i * g + c] : lambda * psi[i * k + (c - g)];
}

// d_geo (when write_geo) = d_hyb[:, :G]; d_psi = λ · d_hyb[:, G:] (overwritten).
__kernel void spectral_fusion_bwd(const int n, const int g, const int k, const float lambda,
                                  const int write_geo, __global const float* d_hyb,
                                  __global float* d_geo, __global float* d_psi) {
  const int w = g + k;
  const int idx = get_global_id(0);
  if (idx >= n * w) return;
  const int i = idx / w, c = idx - i * w;
  if (c >= g) {
    d_psi[i * k + (c - g)] = lambda * d_hyb[idx];
  } else if (write_geo) {
    d_geo[i * g + c] = d_hyb[idx];
  }
}
