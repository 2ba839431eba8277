// dst[i] += src[i] for i < n (summing two contributions to one gradient, e.g. dL/dx through the
// hash grid and through Ψ in SG-NLF's hybrid encoding). One work-item per element.
__kernel void field_accumulate(const int n, __global const float* src, __global float* dst) {
  const int i = get_global_id(0);
  if (i < n) dst[i] += src[i];
}
