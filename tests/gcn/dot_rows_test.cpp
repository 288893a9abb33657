// dot_rows / axpy_rows: the thin matrix-times-few-vectors kernels, against Eigen,
// on lengths that exercise every tail of the vector loops.
#include <drape/nn/dot_rows.hpp>

#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include <string>

TEST_CASE("dot_rows and axpy_rows agree with Eigen on every length and row count", "[gcn][kernels]") {
  INFO("version " << drape::nn::dot_rows_version());
  const std::string version = drape::nn::dot_rows_version();
  CHECK((version == "avx2+fma" || version == "portable"));
  for (int n : {1, 7, 8, 9, 31, 32, 33, 100, 1000}) {
    for (int count : {1, 3, 6}) {
      INFO("n " << n << ", count " << count);
      const int stride = n + 3;  // rows of `others` are padded: the stride is honoured
      const Eigen::VectorXf row = Eigen::VectorXf::Random(n);
      Eigen::MatrixXf others = Eigen::MatrixXf::Random(stride, count);  // column r is other row r
      Eigen::VectorXf out(count);
      drape::nn::dot_rows(row.data(), others.data(), n, stride, count, out.data());
      const Eigen::VectorXf expected = others.topRows(n).transpose() * row;
      CHECK((out - expected).cwiseAbs().maxCoeff() <= 1e-6f * (1.0f + float(n)));
      Eigen::VectorXf portable(count);
      drape::nn::detail::dot_rows_portable(row.data(), others.data(), n, stride, count, portable.data());
      CHECK((portable - expected).cwiseAbs().maxCoeff() <= 1e-6f * (1.0f + float(n)));

      const Eigen::VectorXf scale = Eigen::VectorXf::Random(count);
      Eigen::MatrixXf updated = others;
      drape::nn::axpy_rows(row.data(), scale.data(), n, stride, count, updated.data());
      Eigen::MatrixXf want = others;
      want.topRows(n) += row * scale.transpose();
      CHECK((updated - want).cwiseAbs().maxCoeff() <= 1e-5f);
      Eigen::MatrixXf portable_updated = others;
      drape::nn::detail::axpy_rows_portable(row.data(), scale.data(), n, stride, count, portable_updated.data());
      CHECK((portable_updated - want).cwiseAbs().maxCoeff() <= 1e-5f);
      CHECK(updated.bottomRows(stride - n) == others.bottomRows(stride - n));  // padding untouched
    }
  }
}
