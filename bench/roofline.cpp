// The two ceilings of a roofline on this CPU, one core (doc/roofline.md):
//   * memory bandwidth: a STREAM-like triad a[i] = b[i] + s c[i] over arrays
//     far larger than the last-level cache (bytes counted as STREAM does:
//     3 x 8 B per element; the write-allocate read of a[] is not counted),
//     best of NREP passes;
//   * floating-point peak: independent multiply-adds on 12 accumulator
//     chains, scalar (SSE2 scalar FMA-free: 2 flops per mul+add) and, where
//     the CPU has them, 256-bit AVX2 FMA (the code is compiled for that
//     function only, target attribute, and run only when the CPU says it
//     has AVX2 and FMA).
// Prints "key value" lines (bench/roofline.sh collects them).
//   g++ -O2 -o roofline roofline.cpp && ./roofline [MiB per array, default 256]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

static double now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

static double triad_gbs(size_t n, int nrep)
{
  std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
  const double s = 3.0;
  double best = 1e30;
  for (int r = 0; r < nrep; r++) {
    const double t0 = now();
    double *__restrict pa = a.data();
    const double *__restrict pb = b.data(), *__restrict pc = c.data();
    for (size_t i = 0; i < n; i++) pa[i] = pb[i] + s * pc[i];
    const double t = now() - t0;
    if (t < best) best = t;
  }
  volatile double sink = a[n / 2];    // keep the loop
  (void) sink;
  return 3.0 * 8.0 * n / best * 1e-9;
}

// scalar: 12 independent chains of x = x * m + a (a mul and an add each)
static double scalar_gflops(long iters)
{
  double x[12];
  for (int k = 0; k < 12; k++) x[k] = 1.0 + 1e-3 * k;
  const double m = 0.999999, a = 1e-7;
  const double t0 = now();
  for (long it = 0; it < iters; it++)
    for (int k = 0; k < 12; k++) x[k] = x[k] * m + a;
  const double t = now() - t0;
  double s = 0.0;
  for (int k = 0; k < 12; k++) s += x[k];
  volatile double sink = s;
  (void) sink;
  return 2.0 * 12.0 * iters / t * 1e-9;
}

#if defined(__x86_64__)
__attribute__((target("avx2,fma"))) static double avx2_fma_gflops(long iters)
{
  __m256d x[12];
  for (int k = 0; k < 12; k++) x[k] = _mm256_set1_pd(1.0 + 1e-3 * k);
  const __m256d m = _mm256_set1_pd(0.999999), a = _mm256_set1_pd(1e-7);
  const double t0 = now();
  for (long it = 0; it < iters; it++)
    for (int k = 0; k < 12; k++) x[k] = _mm256_fmadd_pd(x[k], m, a);
  const double t = now() - t0;
  __m256d s = _mm256_setzero_pd();
  for (int k = 0; k < 12; k++) s = _mm256_add_pd(s, x[k]);
  double out[4];
  _mm256_storeu_pd(out, s);
  volatile double sink = out[0];
  (void) sink;
  return 2.0 * 4.0 * 12.0 * iters / t * 1e-9;
}

__attribute__((target("avx512f"))) static double avx512_fma_gflops(long iters)
{
  __m512d x[12];
  for (int k = 0; k < 12; k++) x[k] = _mm512_set1_pd(1.0 + 1e-3 * k);
  const __m512d m = _mm512_set1_pd(0.999999), a = _mm512_set1_pd(1e-7);
  const double t0 = now();
  for (long it = 0; it < iters; it++)
    for (int k = 0; k < 12; k++) x[k] = _mm512_fmadd_pd(x[k], m, a);
  const double t = now() - t0;
  __m512d s = _mm512_setzero_pd();
  for (int k = 0; k < 12; k++) s = _mm512_add_pd(s, x[k]);
  volatile double sink = _mm512_reduce_add_pd(s);
  (void) sink;
  return 2.0 * 8.0 * 12.0 * iters / t * 1e-9;
}
#endif

int main(int argc, char **argv)
{
  const double mib = argc > 1 ? atof(argv[1]) : 256.0;
  const size_t n = static_cast<size_t>(mib * 1024.0 * 1024.0 / 8.0);
  std::printf("triad_array_mib %.0f\n", mib);
  std::printf("triad_gb_per_s %.2f\n", triad_gbs(n, 10));
  // the same triad in the last-level cache (3 x 2 MiB)
  std::printf("triad_l3_gb_per_s %.2f\n", triad_gbs(2 * 1024 * 1024 / 8, 200));
  long iters = 100000000;
  double best = 0.0;
  for (int r = 0; r < 3; r++) {
    const double g = scalar_gflops(iters);
    if (g > best) best = g;
  }
  std::printf("scalar_gflops %.2f\n", best);
#if defined(__x86_64__)
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) {
    best = 0.0;
    for (int r = 0; r < 3; r++) {
      const double g = avx2_fma_gflops(iters / 2);
      if (g > best) best = g;
    }
    std::printf("avx2_fma_gflops %.2f\n", best);
  }
  if (__builtin_cpu_supports("avx512f")) {
    best = 0.0;
    for (int r = 0; r < 3; r++) {
      const double g = avx512_fma_gflops(iters / 4);
      if (g > best) best = g;
    }
    std::printf("avx512_fma_gflops %.2f\n", best);
  }
#endif
  return 0;
}
