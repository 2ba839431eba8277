// Device roofline measured in the benchmark run itself: peak GFLOP/s of a float16-vector FMA
// loop, streaming-copy GB/s and random float2 gathers/s (the harness's probe kernels,
// kernels/roofline/roofline.cl). Measured once per process.
#pragma once

namespace sgnlf::bench {

struct Roofline {
  double gflops = 0;  // float16 FMA loop
  double gbs = 0;     // streaming copy (read + write bytes)
  double gathers = 0;  // random float2 reads per second from a 64 MiB table
};
const Roofline& roofline();

}  // namespace sgnlf::bench
