#pragma once
// The small dense kernels of DriveSystem::AffineRows (private to src/): out = A y + c for R rows,
// K columns, in two instruction sets with the same rounding.

#include <emmintrin.h>

namespace machdyn::detail {

/// out = A y + c: cols[k] picks the k-th column's entry of y, A column-major (R rows a column),
/// c the R constants. With a copy count C > 0: out[i] = y[C + i] for i < C first (q̇ = v), the rows
/// then from out[C] on. Each sum starts at c[r] and adds A[k R + r] y[cols[k]] for k = 0, 1, … in
/// that order, each product rounded before the add (no fused multiply-add): every kernel of one
/// shape gives the same bits.
using RowsKernel = void (*)(const int* cols, int ncols, const double* A, const double* c, const double* y,
                            double* out);

/// The copy counts the kernels exist for: none (contact forces), C = R (a chain's or mode's
/// accelerations), C = R − 3 (a mode with the three energy rates; R ≥ 4).
enum class RowsCopy { none, all, energy };

constexpr int kUnrolledRows = 8;  ///< the unrolled kernels: R = 1…8 rows…
constexpr int kUnrolledCols = 8;  ///< …by K = 1…8 columns

/// Whether this CPU runs AVX (and the OS saves its registers): asked once.
bool cpu_has_avx();

/// The unrolled kernel for R rows, K columns and the copy (R, K in 1…8; nullptr for energy with
/// R ≤ 3): the 256-bit AVX build when `avx`, else the SSE2 build. The caller must ask for avx only
/// when cpu_has_avx().
RowsKernel unrolled_rows_kernel(int R, int K, RowsCopy copy, bool avx);

/// out[0, C + R) = (y[C], …, y[2C − 1], s[0], …, s[R − 1]), the values unchanged, stored as 16-byte
/// pairs (out[2m], out[2m + 1]) and the copies read from y's pairs (y[2m], y[2m + 1]). Why: a
/// stepper's vectorized loops (Dopri5's stages) store and load these arrays in exactly such pairs,
/// and a load that straddles two stores cannot take its data from them; it waits until both reach
/// the cache, once per stage (on AMD Zen 3 some 2.5 % of the travel start-up, docs/benchmarks.md).
/// s is the caller's local array: inlined, the compiler keeps it in registers.
template <int C, int R>
__attribute__((always_inline)) inline void store_in_pairs(const double* y, const double* s, double* out) {
  __m128d yp[C > 0 ? C : 1];
  for (int m = C / 2; m < C; ++m) yp[m] = _mm_loadu_pd(y + 2 * m);
  auto val = [&](int j) {
    if (j >= C) return s[j - C];
    const int i = C + j;
    return i % 2 ? _mm_cvtsd_f64(_mm_unpackhi_pd(yp[i / 2], yp[i / 2])) : _mm_cvtsd_f64(yp[i / 2]);
  };
#pragma GCC unroll 16
  for (int j = 0; j + 1 < C + R; j += 2) _mm_storeu_pd(out + j, _mm_set_pd(val(j + 1), val(j)));
  if constexpr ((C + R) % 2 == 1) out[C + R - 1] = val(C + R - 1);
}

}  // namespace machdyn::detail
