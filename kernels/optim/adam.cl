// Adam over a slice of one flat parameter buffer (method.md §0 "one flat parameter buffer, one
// Adam kernel"), PyTorch's form with bias correction:
//   m ← β1 m + (1 − β1) g;  v ← β2 v + (1 − β2) g²
//   p ← p − lr · (m · c1) / (√v · c2 + ε),  c1 = 1/(1 − β1^t), c2 = 1/√(1 − β2^t)
// g includes the L2 term weight_decay · p. Launched once per parameter group.
__kernel void optim_adam_step(const uint offset, const uint count, const float lr,
                              const float beta1, const float beta2, const float eps,
                              const float c1, const float c2, const float weight_decay,
                              __global float* params, __global const float* grad,
                              __global float* m, __global float* v) {
  const uint i = get_global_id(0);
  if (i >= count) return;
  const uint k = offset + i;
  const float p = params[k];
  const float g = fma(weight_decay, p, grad[k]);
  const float mk = fma(beta1, m[k], (1.0f - beta1) * g);
  const float vk = fma(beta2, v[k], (1.0f - beta2) * g * g);
  m[k] = mk;
  v[k] = vk;
  params[k] = p - lr * (mk * c1) / (sqrt(vk) * c2 + eps);
}
