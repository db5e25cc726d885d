#pragma once
// The small dense kernels of DriveSystem::AffineRows (private to src/): out = A y + c for R rows,
// K columns, in two instruction sets with the same rounding.

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

}  // namespace machdyn::detail
