// basis_times / basis_transpose_times: products of a tall basis with a few
// vectors, against double-precision sums computed here, on sizes that reach
// every tail of the blocked loops (rows of V not a multiple of 4 or 64, rows
// of the small operand not a multiple of 6 or 8, k not a multiple of 16) and
// on strided views (a block of columns of a wider matrix, as the decoder's
// use_k makes).
#include <drape/nn/basis_products.hpp>

#include <drape/errors.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

using drape::MatrixRM;

namespace {

// The largest difference between a float result and the same product in
// double (Eigen's, sharing nothing with the kernels under test).
double worst_error(const Eigen::MatrixXd& exact, const Eigen::Ref<const MatrixRM>& out) {
  return (exact - out.cast<double>()).cwiseAbs().maxCoeff();
}
Eigen::MatrixXd in_double(const Eigen::Ref<const MatrixRM>& m) { return m.cast<double>(); }

}  // namespace

TEST_CASE("basis products agree with double-precision sums on every tail and on strided views", "[gcn][kernels]") {
  INFO("version " << drape::nn::basis_products_version());
  const std::string version = drape::nn::basis_products_version();
  CHECK((version == "avx512f" || version == "portable"));
  for (int n : {1, 3, 4, 5, 9, 67, 130}) {
    for (int k : {1, 15, 16, 17, 33, 100}) {
      for (int m : {1, 2, 5, 6, 7, 8, 9, 24}) {
        INFO("n " << n << ", k " << k << ", m " << m);
        const MatrixRM wide = MatrixRM::Random(n, k + 5);
        const auto v = wide.leftCols(k);  // outer stride k + 5
        const MatrixRM a = MatrixRM::Random(m, k), b = MatrixRM::Random(n, m);

        MatrixRM out = MatrixRM::Constant(n, m, 7.0f);  // overwritten, not added to
        drape::nn::basis_times(v, a, out);
        MatrixRM out_wide = MatrixRM::Constant(m, k + 3, 7.0f);
        auto out_t = out_wide.leftCols(k);  // a strided output; the 3 columns past it untouched
        drape::nn::basis_transpose_times(b, v, out_t);

        // Float sums of k (or n) products of numbers in [-1, 1].
        CHECK(worst_error(in_double(v) * in_double(a).transpose(), out) <= 1e-6 * (k + 1));
        CHECK(worst_error(in_double(b).transpose() * in_double(v), out_t) <= 1e-6 * (n + 1));
        CHECK((out_wide.rightCols(3).array() == 7.0f).all());

        // The same V rounded to bfloat16 and read as 16-bit words: the products
        // of the widened values (a strided view again: stride k + 5).
        std::vector<std::uint16_t> v16(static_cast<std::size_t>(n) * (k + 5));
        MatrixRM widened(n, k);
        for (int i = 0; i < n; ++i)
          for (int j = 0; j < k + 5; ++j) {
            std::uint32_t u;
            const float f = wide(i, j);
            std::memcpy(&u, &f, sizeof u);
            v16[static_cast<std::size_t>(i) * (k + 5) + j] = static_cast<std::uint16_t>(u >> 16);
            if (j < k) {
              const std::uint32_t top = u & 0xFFFF0000u;
              float g;
              std::memcpy(&g, &top, sizeof g);
              widened(i, j) = g;
            }
          }
        const drape::nn::Bfloat16Matrix v_bf16{v16.data(), n, k, k + 5};
        MatrixRM out16 = MatrixRM::Constant(n, m, 7.0f), out16_t = MatrixRM::Constant(m, k, 7.0f);
        drape::nn::basis_times(v_bf16, a, out16);
        drape::nn::basis_transpose_times(b, v_bf16, out16_t);
        CHECK(worst_error(in_double(widened) * in_double(a).transpose(), out16) <= 1e-6 * (k + 1));
        CHECK(worst_error(in_double(b).transpose() * in_double(widened), out16_t) <= 1e-6 * (n + 1));
      }
    }
  }
  MatrixRM out(4, 2);
  CHECK_THROWS_WITH(drape::nn::basis_times(MatrixRM::Zero(4, 3), MatrixRM::Zero(2, 5), out),
                    Catch::Contains("basis_times: shapes [4, 3] and [2, 5] into [4, 2] do not fit"));
  MatrixRM wrong(3, 3);
  CHECK_THROWS_WITH(drape::nn::basis_transpose_times(MatrixRM::Zero(4, 3), MatrixRM::Zero(5, 2), wrong),
                    Catch::Contains("basis_transpose_times"));
}
