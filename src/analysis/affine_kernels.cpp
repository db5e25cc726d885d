#include "analysis/affine_kernels.hpp"

#include <immintrin.h>

#include <array>
#include <utility>

namespace machdyn::detail {

namespace {
// SSE2 (the baseline): for a fixed column count K, unrolled, so the sums stay in registers and no
// loop control is left (a small mode's map: K ≤ 8 columns, R ≤ 8 rows).
template <int R, int C, int K>
void rows_sse2(const int* cols, int, const double* A, const double* c, const double* y, double* out) {
  double s[R];
  for (int r = 0; r < R; ++r) s[r] = c[r];
#pragma GCC unroll 8
  for (int k = 0; k < K; ++k) {
    const double x = y[cols[k]];
#pragma GCC unroll 8
    for (int r = 0; r < R; ++r) s[r] += A[k * R + r] * x;
  }
  store_in_pairs<C, R>(y, s, out);
}

// AVX: the same sums four rows to a register (then two, then one). target("avx") enables no FMA,
// so each product is rounded, then added, in the same order as rows_sse2: the same bits, fewer
// instructions (R = 6, K = 5: 75 → 49).
template <int R, int C, int K>
__attribute__((target("avx"))) void rows_avx(const int* cols, int, const double* A, const double* c,
                                             const double* y, double* out) {
  constexpr int R4 = R / 4, R2 = (R % 4) / 2, R1 = R % 2;
  __m256d s4[R4 > 0 ? R4 : 1];
  __m128d s2 = _mm_setzero_pd();
  double s1 = 0.0;
  for (int q = 0; q < R4; ++q) s4[q] = _mm256_loadu_pd(c + 4 * q);
  if constexpr (R2 > 0) s2 = _mm_loadu_pd(c + 4 * R4);
  if constexpr (R1 > 0) s1 = c[R - 1];
#pragma GCC unroll 8
  for (int k = 0; k < K; ++k) {
    const double* xp = y + cols[k];
    const __m256d x4 = _mm256_broadcast_sd(xp);
    const double* a = A + k * R;
#pragma GCC unroll 4
    for (int q = 0; q < R4; ++q) s4[q] = _mm256_add_pd(s4[q], _mm256_mul_pd(_mm256_loadu_pd(a + 4 * q), x4));
    if constexpr (R2 > 0) s2 = _mm_add_pd(s2, _mm_mul_pd(_mm_loadu_pd(a + 4 * R4), _mm256_castpd256_pd128(x4)));
    if constexpr (R1 > 0) s1 += a[R - 1] * *xp;
  }
  alignas(32) double s[4 * R4 + 3];  // 256-bit sums stored whole would straddle the stepper's pairs
  for (int q = 0; q < R4; ++q) _mm256_store_pd(s + 4 * q, s4[q]);
  if constexpr (R2 > 0) _mm_store_pd(s + 4 * R4, s2);
  if constexpr (R1 > 0) s[R - 1] = s1;
  store_in_pairs<C, R>(y, s, out);
}

// The tables by R (outer) and K (inner) for one copy count; the energy copy exists for R > 3 only.
template <bool Avx, int R, int C, int K>
constexpr RowsKernel pick() {
  if constexpr (Avx) return rows_avx<R, C, K>;
  else return rows_sse2<R, C, K>;
}
template <bool Avx, int R, int... Ks>
constexpr std::array<RowsKernel, sizeof...(Ks)> row_of(RowsCopy copy, std::integer_sequence<int, Ks...>) {
  if (copy == RowsCopy::none) return {pick<Avx, R, 0, Ks + 1>()...};
  if (copy == RowsCopy::all) return {pick<Avx, R, R, Ks + 1>()...};
  if constexpr (R > 3) return {pick<Avx, R, R - 3, Ks + 1>()...};
  else return {};
}
using Table = std::array<std::array<RowsKernel, kUnrolledCols>, kUnrolledRows>;
template <bool Avx, int... Rs>
constexpr Table table(RowsCopy copy, std::integer_sequence<int, Rs...>) {
  return {row_of<Avx, Rs + 1>(copy, std::make_integer_sequence<int, kUnrolledCols>{})...};
}
template <bool Avx>
constexpr std::array<Table, 3> tables() {
  constexpr auto rs = std::make_integer_sequence<int, kUnrolledRows>{};
  return {table<Avx>(RowsCopy::none, rs), table<Avx>(RowsCopy::all, rs), table<Avx>(RowsCopy::energy, rs)};
}
constexpr auto kSse2 = tables<false>();
constexpr auto kAvx = tables<true>();
}  // namespace

bool cpu_has_avx() {
  static const bool has = __builtin_cpu_supports("avx");  // CPUID and the OS's XSAVE state (XGETBV)
  return has;
}

RowsKernel unrolled_rows_kernel(int R, int K, RowsCopy copy, bool avx) {
  if (R < 1 || R > kUnrolledRows || K < 1 || K > kUnrolledCols) return nullptr;
  const auto& t = (avx ? kAvx : kSse2)[static_cast<size_t>(copy)];
  return t[static_cast<size_t>(R - 1)][static_cast<size_t>(K - 1)];
}

}  // namespace machdyn::detail
