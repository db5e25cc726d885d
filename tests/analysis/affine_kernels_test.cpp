// The unrolled kernels of DriveSystem::AffineRows (analysis/affine_kernels.hpp), SSE2 and AVX,
// against a plain loop written here: for every R = 1…8, K = 1…8 and copy count, bit for bit.
#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>
#include <gtest/gtest.h>

#include "analysis/affine_kernels.hpp"

namespace machdyn::detail {
namespace MACHDYN_UNITY_ID {

// The reference: out[i] = y[C + i] for i < C, then each row's sum from c[r], adding the products
// column by column in ascending k, each product rounded before its add (as the header states).
std::vector<double> plain(int R, int C, const std::vector<int>& cols, const std::vector<double>& A,
                          const std::vector<double>& c, const std::vector<double>& y) {
  std::vector<double> out(static_cast<size_t>(C + R));
  for (int i = 0; i < C; ++i) out[static_cast<size_t>(i)] = y[static_cast<size_t>(C + i)];
  for (int r = 0; r < R; ++r) {
    double s = c[static_cast<size_t>(r)];
    for (size_t k = 0; k < cols.size(); ++k) {
      const volatile double p = A[k * static_cast<size_t>(R) + static_cast<size_t>(r)] * y[static_cast<size_t>(cols[k])];
      s += p;  // volatile: the product rounded on its own, whatever the compiler may fuse
    }
    out[static_cast<size_t>(C + r)] = s;
  }
  return out;
}

// Every kernel of one table against plain(), 20 draws each: values over 16 decades with both signs,
// so that the sums round at every add (an add in another order would rarely give the same bits).
void check_table(bool avx) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> mant(-1.0, 1.0);
  std::uniform_int_distribution<int> exp10(-8, 8);
  auto value = [&] { return mant(rng) * std::pow(10.0, exp10(rng)); };
  for (const RowsCopy copy : {RowsCopy::none, RowsCopy::all, RowsCopy::energy})
    for (int R = 1; R <= kUnrolledRows; ++R)
      for (int K = 1; K <= kUnrolledCols; ++K) {
        const RowsKernel kernel = unrolled_rows_kernel(R, K, copy, avx);
        if (copy == RowsCopy::energy && R <= 3) {
          EXPECT_EQ(kernel, nullptr) << "R " << R;
          continue;
        }
        ASSERT_NE(kernel, nullptr) << "R " << R << " K " << K;
        const int C = copy == RowsCopy::none ? 0 : copy == RowsCopy::all ? R : R - 3;
        for (int trial = 0; trial < 20; ++trial) {
          const int ny = 2 * C + 2 * kUnrolledCols;
          std::vector<double> y(static_cast<size_t>(ny)), A(static_cast<size_t>(R * K)), c(static_cast<size_t>(R));
          for (auto& v : y) v = value();
          for (auto& v : A) v = value();
          for (auto& v : c) v = value();
          std::vector<int> cols;  // K distinct ascending columns of y
          for (int j = 0; static_cast<int>(cols.size()) < K; ++j)
            if (rng() % 2 == 0 || ny - j == K - static_cast<int>(cols.size())) cols.push_back(j);
          std::vector<double> out(static_cast<size_t>(C + R) + 1, -7.0);  // one more: nothing written past
          kernel(cols.data(), K, A.data(), c.data(), y.data(), out.data());
          const auto want = plain(R, C, cols, A, c, y);
          for (size_t i = 0; i < want.size(); ++i)
            ASSERT_EQ(std::bit_cast<std::uint64_t>(out[i]), std::bit_cast<std::uint64_t>(want[i]))
                << (avx ? "avx" : "sse2") << " R " << R << " K " << K << " C " << C << " i " << i;
          EXPECT_EQ(out.back(), -7.0);
        }
      }
}

TEST(AffineKernels, Sse2TableMatchesPlainLoopBitForBit) { check_table(false); }

TEST(AffineKernels, AvxTableMatchesPlainLoopBitForBit) {
  if (!cpu_has_avx()) GTEST_SKIP() << "this CPU has no AVX";
  check_table(true);
}

TEST(AffineKernels, OutOfRangeShapesHaveNoKernel) {
  EXPECT_EQ(unrolled_rows_kernel(0, 1, RowsCopy::none, false), nullptr);
  EXPECT_EQ(unrolled_rows_kernel(9, 1, RowsCopy::none, false), nullptr);
  EXPECT_EQ(unrolled_rows_kernel(1, 9, RowsCopy::all, false), nullptr);
}

}  // namespace
}  // namespace machdyn::detail
