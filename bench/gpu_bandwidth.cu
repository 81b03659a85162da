// gpu_bandwidth: the copy ceilings of the GPU for scripts/gpu-check.sh
// (doc/kokkos-cuda.md, the roofline bound of the /kk step), FP64:
//   device memory: cudaMemcpy device to device (read + write) and a STREAM
//   triad kernel a = b + s c (two reads, one write), 1 GiB arrays;
//   PCIe/NVLink-C2C: pinned host to device and device to host, 256 MiB.
// Best of 10 repetitions, timed with CUDA events. Prints one line per
// measurement: "bandwidth NAME GB/s BYTES_PER_REP". Built by
// scripts/gpu-bundle.sh with the bundle's nvcc (static CUDA runtime).
#include <cstdio>
#include <cstdlib>
#include <cuda_runtime.h>

#define CHECK(call)                                                                   \
  do {                                                                                \
    cudaError_t e_ = (call);                                                          \
    if (e_ != cudaSuccess) {                                                          \
      std::fprintf(stderr, "gpu_bandwidth: %s: %s\n", #call, cudaGetErrorString(e_)); \
      std::exit(1);                                                                   \
    }                                                                                 \
  } while (0)

__global__ void triad(double *a, const double *b, const double *c, double s, size_t n)
{
  for (size_t i = blockIdx.x * (size_t) blockDim.x + threadIdx.x; i < n;
       i += (size_t) gridDim.x * blockDim.x)
    a[i] = b[i] + s * c[i];
}

template <class F> static double best_ms(F f, int reps)
{
  cudaEvent_t t0, t1;
  CHECK(cudaEventCreate(&t0));
  CHECK(cudaEventCreate(&t1));
  f();    // warm-up
  CHECK(cudaDeviceSynchronize());
  float best = 1e30f;
  for (int r = 0; r < reps; r++) {
    CHECK(cudaEventRecord(t0));
    f();
    CHECK(cudaEventRecord(t1));
    CHECK(cudaEventSynchronize(t1));
    float ms;
    CHECK(cudaEventElapsedTime(&ms, t0, t1));
    if (ms < best) best = ms;
  }
  return best;
}

int main()
{
  cudaDeviceProp p;
  CHECK(cudaGetDeviceProperties(&p, 0));
  int rt = 0, drv = 0;
  CHECK(cudaRuntimeGetVersion(&rt));
  CHECK(cudaDriverGetVersion(&drv));
  std::printf("device %s sm_%d%d, %.1f GiB, %d SMs, runtime %d, driver API %d\n", p.name, p.major,
              p.minor, p.totalGlobalMem / 1073741824.0, p.multiProcessorCount, rt, drv);
  const size_t n = (size_t) 1 << 27;    // 2^27 doubles = 1 GiB per array
  double *a, *b, *c;
  CHECK(cudaMalloc(&a, n * sizeof(double)));
  CHECK(cudaMalloc(&b, n * sizeof(double)));
  CHECK(cudaMalloc(&c, n * sizeof(double)));
  CHECK(cudaMemset(b, 0, n * sizeof(double)));
  CHECK(cudaMemset(c, 0, n * sizeof(double)));
  const int reps = 10;
  double ms = best_ms([&] { CHECK(cudaMemcpy(a, b, n * sizeof(double), cudaMemcpyDeviceToDevice)); }, reps);
  std::printf("bandwidth d2d_copy %.1f GB/s %zu\n", 2.0 * n * sizeof(double) / ms / 1e6,
              2 * n * sizeof(double));
  const int threads = 256, blocks = 4 * p.multiProcessorCount * 8;
  ms = best_ms([&] { triad<<<blocks, threads>>>(a, b, c, 3.0, n); }, reps);
  CHECK(cudaGetLastError());
  std::printf("bandwidth triad %.1f GB/s %zu\n", 3.0 * n * sizeof(double) / ms / 1e6,
              3 * n * sizeof(double));
  const size_t m = n / 4;
  double *h;
  CHECK(cudaMallocHost(&h, m * sizeof(double)));
  for (size_t i = 0; i < m; i++) h[i] = 0.0;
  ms = best_ms([&] { CHECK(cudaMemcpy(a, h, m * sizeof(double), cudaMemcpyHostToDevice)); }, reps);
  std::printf("bandwidth h2d_pinned %.1f GB/s %zu\n", m * sizeof(double) / ms / 1e6, m * sizeof(double));
  ms = best_ms([&] { CHECK(cudaMemcpy(h, a, m * sizeof(double), cudaMemcpyDeviceToHost)); }, reps);
  std::printf("bandwidth d2h_pinned %.1f GB/s %zu\n", m * sizeof(double) / ms / 1e6, m * sizeof(double));
  CHECK(cudaFreeHost(h));
  CHECK(cudaFree(a));
  CHECK(cudaFree(b));
  CHECK(cudaFree(c));
  return 0;
}
