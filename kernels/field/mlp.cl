// One fully connected layer of a small MLP (method.md §0 density MLP and LiDAR head, §4.1 Ψ):
// register-tiled float16-vector GEMMs (performance.md) for forward, input backward and a
// deterministic two-phase weight-gradient reduction (fixed chunking, fixed summation order).
//
// Parameters of the layer (at w_off): W_t[N_IN][OUT_PAD] then bias b[OUT_PAD], i.e. a
// (N_IN + 1) × OUT_PAD row-major block whose last row is the bias. Padding columns are zero.
// Activations are point-major rows. Defines (set by runtime/field/mlp.cpp):
//   N_IN, IN_STRIDE (row stride of the input), IN_PAD = round_up(N_IN, 16),
//   OUT, OUT_PAD = round_up(OUT, 16), OUT_STRIDE (row stride of the output),
//   ACT (activation of this layer), STORE_PRE (1: also write pre-activations, OUT_PAD stride),
//   PREV_ACT (activation of the previous layer, -1: none = input of the MLP),
//   PREV_PRE (1: previous layer's derivative from its pre-activations), DIN_STRIDE,
//   PTS (points per work-item), ROWS (weight rows per work-item in the weight gradient),
//   IN_OFFSET / DIN_OFFSET (first column of the input / of d_in within its row),
//   GROUP_BIAS (1: the pre-activation starts from a per-group row gbias[point / group], or
//   gbias[gidx[point]] when `indexed`, instead of the bias: layer 0 of an MLP with grouped
//   inputs, see runtime/field/mlp.hpp),
//   HAS_BIAS (0: a bias-free layer: the bias row is neither read nor given a gradient; it
//   stays in the layout, zero, so that bias-free and biased MLPs share one layout),
//   TOWER_IN, TOWER_OUT (a later layer of an MLP of towers: input i and output o are joined
//   only when i / TOWER_IN == o / TOWER_OUT, every other weight is a structural zero; 0: dense).
//   The kernels skip the zero blocks where a 16-wide tile lies in one tower (the forward's
//   and the weight gradient's output tiles: TOWER_OUT % 16 == 0; the input backward's input
//   tiles: TOWER_IN % 16 == 0). A skipped term is an exact zero (x · 0), so the results are
//   those of the dense products; the off-tower weight gradient is zeroed by
//   field_mlp_tower_mask in any case.
#include "field/mlp_layer.clh"
// Output tiles within one tower (forward, weight gradient) / input tiles (input backward).
#define TOWER_OUT_TILES (TOWER_IN > 0 && TOWER_OUT > 0 && TOWER_OUT % 16 == 0)
#define TOWER_IN_TILES (TOWER_IN > 0 && TOWER_OUT > 0 && TOWER_IN % 16 == 0)
// d_in rows are whole padded vectors (full-width stores) only without stride or offset.
#if DIN_STRIDE == IN_PAD && DIN_OFFSET == 0
#define DIN_DENSE 1
#else
#define DIN_DENSE 0
#endif

inline float16 act_fwd(float16 z, int a) {
  if (a == ACT_RELU) return fmax(z, (float16)(0.0f));
  if (a == ACT_TANH) return tanh(z);
  if (a == ACT_SOFTPLUS) return log1p(exp(-fabs(z))) + fmax(z, (float16)(0.0f));
  if (a == ACT_SINE) return sin(z);
  return z;
}
// Derivative of the activation from its output y (relu, tanh, softplus, none).
inline float16 act_grad_post(float16 y, int a) {
  if (a == ACT_RELU) return select((float16)(0.0f), (float16)(1.0f), y > (float16)(0.0f));
  if (a == ACT_TANH) return (float16)(1.0f) - y * y;
  if (a == ACT_SOFTPLUS) return -expm1(-y);
  return (float16)(1.0f);
}
// Derivative of the activation from its input z (every activation).
inline float16 act_grad_pre(float16 z, int a) {
  if (a == ACT_RELU) return select((float16)(0.0f), (float16)(1.0f), z > (float16)(0.0f));
  if (a == ACT_TANH) {
    const float16 t = tanh(z);
    return (float16)(1.0f) - t * t;
  }
  if (a == ACT_SOFTPLUS) return (float16)(1.0f) / ((float16)(1.0f) + exp(-z));
  if (a == ACT_SINE) return cos(z);
  return (float16)(1.0f);
}

// Writes lanes o0.. of a row: full vector when the row is padded, else masked to OUT/N_IN.
inline void store_row(float16 v, __global float* row, int o0, int width, int padded) {
  if (padded) {
    vstore16(v, 0, row + o0);
  } else {
    float t[16];
    vstore16(v, 0, t);
    for (int k = 0; k < 16; ++k)
      if (o0 + k < width) row[o0 + k] = t[k];
  }
}

// Forward: out = act(in · W_t + b), or with GROUP_BIAS act(in · W_t + gbias[g]), g = point /
// group (indexed = 0) or gidx[point] (indexed = 1: groups of varying size).
// Work-item = PTS points × 16 outputs.
__kernel void field_mlp_fwd(const int n, __global const float* params, const uint w_off,
                            __global const float* in, __global float* out,
                            __global float* pre, __global const float* gbias, const int group,
                            __global const int* gidx, const int indexed) {
  const int p0 = get_global_id(0) * PTS;
  const int o0 = get_global_id(1) * 16;
  if (p0 >= n) return;
  __global const float* W = params + w_off;
  float16 acc[PTS];
  __global const float* rows[PTS];
#if !GROUP_BIAS && HAS_BIAS
  const float16 b = vload16(0, W + N_IN * OUT_PAD + o0);
#elif !GROUP_BIAS
  const float16 b = (float16)(0.0f);
#endif
#pragma unroll
  for (int p = 0; p < PTS; ++p) {
#if GROUP_BIAS
    const int pp = min(p0 + p, n - 1);
    acc[p] = vload16(0, gbias + (size_t)(indexed ? gidx[pp] : pp / group) * OUT_PAD + o0);
#else
    acc[p] = b;
#endif
    rows[p] = in + (size_t)min(p0 + p, n - 1) * IN_STRIDE + IN_OFFSET;
  }
#if TOWER_OUT_TILES
  const int i_lo = (o0 / TOWER_OUT) * TOWER_IN, i_hi = min(N_IN, i_lo + TOWER_IN);
#else
  const int i_lo = 0, i_hi = N_IN;
#endif
  for (int i = i_lo; i < i_hi; ++i) {
    const float16 w = vload16(0, W + i * OUT_PAD + o0);
#pragma unroll
    for (int p = 0; p < PTS; ++p) acc[p] = fma((float16)(rows[p][i]), w, acc[p]);
  }
#pragma unroll
  for (int p = 0; p < PTS; ++p) {
    if (p0 + p < n) {
#if STORE_PRE
      vstore16(acc[p], 0, pre + (size_t)(p0 + p) * OUT_PAD + o0);
#endif
      store_row(act_fwd(acc[p], ACT), out + (size_t)(p0 + p) * OUT_STRIDE, o0, OUT,
                OUT_STRIDE == OUT_PAD);
    }
  }
}

// Gradient at the pre-activation of the last layer: d_pre = d_out ⊙ act'(·); zero padding.
// `y` is the layer output (stride OUT_STRIDE) or, with STORE_PRE, the pre-activation (OUT_PAD).
__kernel void field_mlp_bwd_out(const int n, __global const float* d_out, __global const float* y,
                                __global float* d_pre) {
  const int i = get_global_id(0);
  if (i >= n) return;
  for (int o0 = 0; o0 < OUT_PAD; o0 += 16) {
    float t[16], a[16];
    for (int k = 0; k < 16; ++k) {
      const int o = o0 + k;
      t[k] = o < OUT ? d_out[(size_t)i * OUT_STRIDE + o] : 0.0f;
#if STORE_PRE
      a[k] = o < OUT ? y[(size_t)i * OUT_PAD + o] : 0.0f;
#else
      a[k] = o < OUT ? y[(size_t)i * OUT_STRIDE + o] : 0.0f;
#endif
    }
    const float16 g = vload16(0, t);
#if ACT == ACT_NONE
    const float16 d = g;
#elif STORE_PRE
    const float16 d = g * act_grad_pre(vload16(0, a), ACT);
#else
    const float16 d = g * act_grad_post(vload16(0, a), ACT);
#endif
    vstore16(d, 0, d_pre + (size_t)i * OUT_PAD + o0);
  }
}

// Weight gradient, phase 1: partial[c] = Σ_{points of chunk c, in order} [in, 1]ᵀ · d_pre.
// Work-item = chunk × ROWS input rows × 16 outputs; the last row block (id ceil(N_IN/ROWS))
// computes the bias row Σ d_pre alone, so the main loop is plain loads and FMAs.
#define ROW_BLOCKS ((N_IN + ROWS - 1) / ROWS)
__kernel void field_mlp_bwd_wgt(const int n, const int chunk, __global const float* in,
                                __global const float* d_pre, __global float* partial) {
  const int c = get_global_id(0);
  const int rb = get_global_id(1);
  const int o0 = get_global_id(2) * 16;
  const int begin = c * chunk, end = min(n, begin + chunk);
  __global float* dst = partial + (size_t)c * (N_IN + 1) * OUT_PAD;
  if (rb == ROW_BLOCKS) {
    float16 acc = (float16)(0.0f);
#if HAS_BIAS
    for (int i = begin; i < end; ++i) acc += vload16(0, d_pre + (size_t)i * OUT_PAD + o0);
#endif
    vstore16(acc, 0, dst + (size_t)N_IN * OUT_PAD + o0);
    return;
  }
  const int r0 = rb * ROWS;
#if TOWER_OUT_TILES
  {  // A row block wholly outside this output tile's tower: structural zeros.
    const int t_lo = (o0 / TOWER_OUT) * TOWER_IN;
    if (r0 + ROWS <= t_lo || r0 >= t_lo + TOWER_IN) {
      for (int r = 0; r < ROWS; ++r)
        if (r0 + r < N_IN) vstore16((float16)(0.0f), 0, dst + (size_t)(r0 + r) * OUT_PAD + o0);
      return;
    }
  }
#endif
  float16 acc[ROWS];
  int col[ROWS];
#pragma unroll
  for (int r = 0; r < ROWS; ++r) {
    acc[r] = (float16)(0.0f);
    col[r] = min(r0 + r, N_IN - 1);  // rows past N_IN repeat the last one; not stored
  }
  for (int i = begin; i < end; ++i) {
    const float16 d = vload16(0, d_pre + (size_t)i * OUT_PAD + o0);
    __global const float* row = in + (size_t)i * IN_STRIDE + IN_OFFSET;
#pragma unroll
    for (int r = 0; r < ROWS; ++r) acc[r] = fma((float16)(row[col[r]]), d, acc[r]);
  }
#pragma unroll
  for (int r = 0; r < ROWS; ++r)
    if (r0 + r < N_IN) vstore16(acc[r], 0, dst + (size_t)(r0 + r) * OUT_PAD + o0);
}

// Weight gradient, phase 2: grad[w_off + k] = Σ_c partial[c][k] in chunk order (overwrites).
__kernel void field_mlp_bwd_reduce(const int n_chunks, __global const float* partial,
                                   __global float* grad, const uint w_off) {
  const int k = get_global_id(0);
  const int count = (N_IN + 1) * OUT_PAD;
  if (k >= count) return;
  float s = 0.0f;
  for (int c = 0; c < n_chunks; ++c) s += partial[(size_t)c * count + k];
  grad[w_off + k] = s;
}

// W transposed to [OUT_PAD][IN_PAD] (zero padded) for the input backward's vector loads.
__kernel void field_mlp_transpose(__global const float* params, const uint w_off,
                                  __global float* wt) {
  const int i = get_global_id(0);
  const int o = get_global_id(1);
  if (i >= IN_PAD || o >= OUT_PAD) return;
  wt[o * IN_PAD + i] = i < N_IN ? params[w_off + i * OUT_PAD + o] : 0.0f;
}

// Input backward: d_in = d_pre · W (PTS points × 16 inputs per work-item). With PREV_ACT >= 0
// the previous layer's activation derivative is applied (prev = its output, stride IN_STRIDE,
// or its pre-activation with PREV_PRE), giving that layer's d_pre (stride IN_PAD).
__kernel void field_mlp_bwd_in(const int n, __global const float* wt, __global const float* d_pre,
                               __global const float* prev, __global float* d_in) {
  const int p0 = get_global_id(0) * PTS;
  const int i0 = get_global_id(1) * 16;
  if (p0 >= n) return;
  float16 acc[PTS];
  __global const float* rows[PTS];
#pragma unroll
  for (int p = 0; p < PTS; ++p) {
    acc[p] = (float16)(0.0f);
    rows[p] = d_pre + (size_t)min(p0 + p, n - 1) * OUT_PAD;
  }
#if TOWER_IN_TILES
  const int o_lo = (i0 / TOWER_IN) * TOWER_OUT, o_hi = min(OUT, o_lo + TOWER_OUT);
#else
  const int o_lo = 0, o_hi = OUT;
#endif
  for (int o = o_lo; o < o_hi; ++o) {
    const float16 w = vload16(0, wt + o * IN_PAD + i0);
#pragma unroll
    for (int p = 0; p < PTS; ++p) acc[p] = fma((float16)(rows[p][o]), w, acc[p]);
  }
#pragma unroll
  for (int p = 0; p < PTS; ++p) {
    if (p0 + p >= n) continue;
    const size_t row = (size_t)(p0 + p);
#if PREV_ACT < 0
    store_row(acc[p], d_in + row * DIN_STRIDE + DIN_OFFSET, i0, N_IN, DIN_DENSE);
#elif PREV_ACT == ACT_NONE
    vstore16(acc[p], 0, d_in + row * IN_PAD + i0);
#elif PREV_PRE
    vstore16(acc[p] * act_grad_pre(vload16(0, prev + row * IN_PAD + i0), PREV_ACT), 0,
             d_in + row * IN_PAD + i0);
#else
    vstore16(acc[p] * act_grad_post(vload16(0, prev + row * IN_STRIDE + i0), PREV_ACT), 0,
             d_in + row * IN_PAD + i0);
#endif
  }
}

// Grouped inputs, backward: d_group[g] = Σ_{k in group g} d_pre[k] (OUT_PAD wide, in order:
// deterministic); group g holds points [g·group, (g + 1)·group), or [goff[g], goff[g + 1])
// when `indexed` (possibly none: a zero row). Work-item = group × 16 outputs.
__kernel void field_mlp_group_sum(const int n_groups, const int group,
                                  __global const float* d_pre, __global float* d_group,
                                  __global const int* goff, const int indexed) {
  const int g = get_global_id(0);
  const int o0 = get_global_id(1) * 16;
  if (g >= n_groups) return;
  float16 acc = (float16)(0.0f);
  const int k0 = indexed ? goff[g] : g * group, k1 = indexed ? goff[g + 1] : (g + 1) * group;
  for (int k = k0; k < k1; ++k)
    acc += vload16(0, d_pre + (size_t)k * OUT_PAD + o0);
  vstore16(acc, 0, d_group + (size_t)g * OUT_PAD + o0);
}

// Towers (runtime/field/mlp.hpp): zeroes the gradient of the structurally zero off-tower
// weights, grad[g_off + k] = 0 where keep[k] == 0, over the slice from layer 1 on.
__kernel void field_mlp_tower_mask(const int count, __global const uchar* keep,
                                   __global float* grad, const uint g_off) {
  const int k = get_global_id(0);
  if (k < count && !keep[k]) grad[g_off + k] = 0.0f;
}
