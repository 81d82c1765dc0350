#pragma once
// Lanes: a small fixed-width vector of doubles for the batched element kernels (one element per lane).
//
// Built on the GCC/Clang vector extension, so the same source is portable: with AVX (FSI_NATIVE=ON on this
// machine) 4 lanes in one ymm register; without it (the portable SSE2 build) 2 lanes in one xmm register. The
// kernels stay branch-free: a per-lane condition is a mask (all bits set where true) and a selection is a
// blend (`select`), never a jump.

#include <cmath>
#include <cstdint>
#include <cstring>

#if defined(__AVX__)
#include <immintrin.h>
#elif defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace fsi::structure::lanes {

/// Elements per batch: 4 doubles, one AVX register (the gather and scatter below are written for it; wider
/// AVX-512 lanes were not tried: this Zen core runs them as two 256-bit halves). Without AVX, 2 (one SSE2
/// register): a 4-lane vector there would be passed between functions in memory (GCC's -Wpsabi).
#if defined(__AVX__)
constexpr int kWidth = 4;
#else
constexpr int kWidth = 2;
#endif

typedef double Vd __attribute__((vector_size(kWidth * sizeof(double))));
typedef std::int64_t Vm __attribute__((vector_size(kWidth * sizeof(double))));  ///< lane mask (0 or ~0)

inline Vd splat(double s) {
  Vd v{};
  for (int l = 0; l < kWidth; ++l) v[l] = s;
  return v;
}

/// kWidth consecutive doubles from p (no alignment needed).
inline Vd load(const double* p) {
  Vd v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

/// Per-lane blend: a where the mask is set, b elsewhere.
inline Vd select(Vm mask, Vd a, Vd b) {
  return mask ? a : b;
}

/// std::max's order: a unless a < b.
inline Vd max(Vd a, Vd b) {
  return a < b ? b : a;
}
/// std::min's order: a unless b < a.
inline Vd min(Vd a, Vd b) {
  return b < a ? b : a;
}
inline Vd abs(Vd a) {
  return a < 0.0 ? -a : a;
}

/// Square root of every lane (the hardware instruction where there is one; the scalar call otherwise).
inline Vd sqrt(Vd a) {
#if defined(__AVX__)
  static_assert(kWidth == 4, "one ymm register per lane vector");
  return Vd(_mm256_sqrt_pd(__m256d(a)));
#elif defined(__SSE2__)
  static_assert(kWidth == 2, "one xmm register per lane vector");
  return Vd(_mm_sqrt_pd(__m128d(a)));
#else
  Vd r{};
  for (int l = 0; l < kWidth; ++l) r[l] = std::sqrt(a[l]);
  return r;
#endif
}

/// kWidth doubles of v to p (no alignment needed).
inline void store(double* p, Vd v) {
  std::memcpy(p, &v, sizeof v);
}

/// atan2(y, x) of every lane, branch-free: the ratio of the smaller to the larger magnitude reduced to
/// |r| ≤ tan(π/8) (through atan(t) = π/4 + atan((t − 1)/(t + 1)) above it), atan(r) = r + r³ P(r²) with
/// P of degree 10 evaluated by Estrin's scheme (a Chebyshev interpolant of (atan(r)/r − 1)/r², fitted in
/// 50-digit arithmetic; truncation below 5e-18 relative), then the octant and quadrant by blends. Within a
/// few units in the last place of std::atan2 (tests/unit/test_lanes_atan2.cpp); signed zeros as std::atan2
/// takes them.
inline Vd atan2(Vd y, Vd x) {
  constexpr double kPi = 3.14159265358979323846, kTanPi8 = 0.41421356237309504880;
  const Vd ax = abs(x), ay = abs(y);
  const Vm swap = ay > ax;
  const Vd num = select(swap, ax, ay), den = select(swap, ay, ax);
  const Vm big = num > kTanPi8 * den;
  const Vd safeDen = select(den > 0.0, den, splat(1.0));
  const Vd r = select(big, num - den, num) / select(big, num + den, safeDen);
  const Vd u = r * r;
  // P(u) = Σ c_k u^k by Estrin's scheme: pairs, then u², u⁴ and u⁸ (four dependent steps after u, where
  // Horner's rule chains ten multiply-adds; the angle is on the bending kernel's critical path).
  const Vd u2 = u * u, u4 = u2 * u2, u8 = u4 * u4;
  const Vd q0 = -0.3333333333333333 + 0.1999999999999552 * u;
  const Vd q1 = -0.14285714284666542 + 0.11111111015256361 * u;
  const Vd q2 = -0.09090904578123903 + 0.07692183190826087 * u;
  const Vd q3 = -0.06664511447381948 + 0.0585814891280221 * u;
  const Vd q4 = -0.0508544973794026 + 0.03923165829558719 * u;
  const Vd s0 = q0 + q1 * u2, s1 = q2 + q3 * u2, s2 = q4 - 0.01917688711906226 * u2;
  const Vd p = (s0 + s1 * u4) + s2 * u8;
  Vd a = r + r * u * p;
  a = select(big, a + 0.25 * kPi, a);
  a = select(swap, 0.5 * kPi - a, a);
  Vm signX, signY;
  std::memcpy(&signX, &x, sizeof x);
  std::memcpy(&signY, &y, sizeof y);
  a = select(signX < 0, kPi - a, a);
  return select(signY < 0, -a, a);
}

/// Gathers the xyz triples at p[0..kWidth) into lane vectors out[0..2] = x, y, z of every lane. The AVX
/// version builds the vectors in registers (through memory the 8-byte writes and the 32-byte read would
/// stall the store forwarding).
inline void gather3At(const double* const p[kWidth], Vd out[3]) {
#if defined(__AVX__)
  const __m256d a = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(p[0])), _mm_loadu_pd(p[2]), 1);
  const __m256d b = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(p[1])), _mm_loadu_pd(p[3]), 1);
  out[0] = Vd(_mm256_unpacklo_pd(a, b));  // x0 x1 x2 x3
  out[1] = Vd(_mm256_unpackhi_pd(a, b));  // y0 y1 y2 y3
  const __m128d z01 = _mm_loadh_pd(_mm_load_sd(p[0] + 2), p[1] + 2);
  const __m128d z23 = _mm_loadh_pd(_mm_load_sd(p[2] + 2), p[3] + 2);
  out[2] = Vd(_mm256_insertf128_pd(_mm256_castpd128_pd256(z01), z23, 1));
#else
  // Through an array: GCC 12 takes lane-by-lane writes into a vector for reads of an uninitialised one.
  for (int i = 0; i < 3; ++i) {
    double t[kWidth];
    for (int l = 0; l < kWidth; ++l) t[l] = p[l][i];
    out[i] = load(t);
  }
#endif
}

/// Gathers the coordinates of kWidth nodes (xyz-interleaved array x, node indices idx) into lane vectors
/// out[0..2] = x, y, z of every lane.
inline void gather3(const double* __restrict x, const int* idx, Vd out[3]) {
  const double* p[kWidth];
  for (int l = 0; l < kWidth; ++l) p[l] = x + 3 * idx[l];
  gather3At(p, out);
}

/// The same with the nodes given by their offsets in x (3 × node index, laid out once by the caller: no
/// index arithmetic per lane).
inline void gather3Offsets(const double* __restrict x, const int* offset, Vd out[3]) {
  const double* p[kWidth];
  for (int l = 0; l < kWidth; ++l) p[l] = x + offset[l];
  gather3At(p, out);
}

/// Adds lane l of in[0..2] (x, y, z) to the xyz triple at q[l], lane after lane (lanes may name the same
/// node).
inline void scatterAdd3At(double* const q[kWidth], const Vd in[3]) {
#if defined(__AVX__)
  const __m256d a = _mm256_unpacklo_pd(__m256d(in[0]), __m256d(in[1]));  // x0 y0 x2 y2
  const __m256d b = _mm256_unpackhi_pd(__m256d(in[0]), __m256d(in[1]));  // x1 y1 x3 y3
  const __m128d xy[4] = {_mm256_castpd256_pd128(a), _mm256_castpd256_pd128(b), _mm256_extractf128_pd(a, 1),
                         _mm256_extractf128_pd(b, 1)};
  const __m128d zlo = _mm256_castpd256_pd128(__m256d(in[2])), zhi = _mm256_extractf128_pd(__m256d(in[2]), 1);
  const double z[4] = {_mm_cvtsd_f64(zlo), _mm_cvtsd_f64(_mm_unpackhi_pd(zlo, zlo)), _mm_cvtsd_f64(zhi),
                       _mm_cvtsd_f64(_mm_unpackhi_pd(zhi, zhi))};
  for (int l = 0; l < 4; ++l) {
    _mm_storeu_pd(q[l], _mm_add_pd(_mm_loadu_pd(q[l]), xy[l]));
    q[l][2] += z[l];
  }
#else
  for (int l = 0; l < kWidth; ++l)
    for (int i = 0; i < 3; ++i) q[l][i] += in[i][l];
#endif
}

/// Adds lane l of in[0..2] (x, y, z) to node idx[l] of the xyz-interleaved array f, lane after lane (lanes
/// may name the same node).
inline void scatterAdd3(double* __restrict f, const int* idx, const Vd in[3]) {
  double* q[kWidth];
  for (int l = 0; l < kWidth; ++l) q[l] = f + 3 * idx[l];
  scatterAdd3At(q, in);
}

/// The same with the nodes given by their offsets in f (3 × node index).
inline void scatterAdd3Offsets(double* __restrict f, const int* offset, const Vd in[3]) {
  double* q[kWidth];
  for (int l = 0; l < kWidth; ++l) q[l] = f + offset[l];
  scatterAdd3At(q, in);
}

/// Loads kWidth records of n doubles each (record l at p + n l) as n lane vectors: out[j][l] = p[n l + j].
template <int n>
inline void loadRecords(const double* __restrict p, Vd out[n]) {
#if defined(__AVX__)
  if constexpr (n == 4) {
    const __m256d r0 = _mm256_loadu_pd(p), r1 = _mm256_loadu_pd(p + 4), r2 = _mm256_loadu_pd(p + 8),
                  r3 = _mm256_loadu_pd(p + 12);
    const __m256d t0 = _mm256_unpacklo_pd(r0, r1),
                  t1 = _mm256_unpackhi_pd(r0, r1);  // a0 a1 c0 c1, b0 b1 d0 d1
    const __m256d t2 = _mm256_unpacklo_pd(r2, r3), t3 = _mm256_unpackhi_pd(r2, r3);
    out[0] = Vd(_mm256_permute2f128_pd(t0, t2, 0x20));
    out[1] = Vd(_mm256_permute2f128_pd(t1, t3, 0x20));
    out[2] = Vd(_mm256_permute2f128_pd(t0, t2, 0x31));
    out[3] = Vd(_mm256_permute2f128_pd(t1, t3, 0x31));
    return;
  }
#endif
  for (int j = 0; j < n; ++j) {
    double t[kWidth];
    for (int l = 0; l < kWidth; ++l) t[l] = p[n * l + j];
    out[j] = load(t);
  }
}

/// Sum of the lanes (the order is fixed, so a batched sum is reproducible).
inline double sum(Vd a) {
  double s = 0.0;
  for (int l = 0; l < kWidth; ++l) s += a[l];
  return s;
}

}  // namespace fsi::structure::lanes
