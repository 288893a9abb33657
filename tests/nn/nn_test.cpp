// The framework's dense-layer building blocks (drape/nn): values against plain
// loops, adjointness of im2col/col2im, and gradients against finite differences
// through small wrapper nodes.
#include <drape/errors.hpp>
#include <drape/gradcheck.hpp>
#include <drape/nn/activation.hpp>
#include <drape/nn/conv1d.hpp>
#include <drape/nn/dense_stack.hpp>
#include <drape/nn/gemm.hpp>
#include <drape/nn/init.hpp>
#include <drape/nn/linear.hpp>
#include <drape/nn/skinny_gemm.hpp>

#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <string>
#include <vector>
#include <random>

using namespace drape;

namespace {

MatrixRM random_matrix(int rows, int cols, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  MatrixRM m(rows, cols);
  for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = u(rng);
  return m;
}

Tensor random_tensor(int batch, int rows, int cols, std::uint64_t seed) {
  Tensor t(batch, rows, cols);
  t.flat() = random_matrix(batch * rows, cols, seed);
  return t;
}

// A node around a DenseStack: [R, in] -> [R, out] per row.
class StackNode final : public Node {
 public:
  StackNode(std::vector<int> sizes, nn::Activation hidden, nn::Activation last) : stack_(sizes, hidden, last) {}
  ShapeMap setup(const ShapeMap& in, const NodeContext& ctx) override {
    stack_.create_weights(*this, "s_", ctx.seed);
    return {{"y", {in.at("x").rows, stack_.out()}}};
  }
  void forward(const TensorIn& in, const TensorOut& out) override { out.at("y")->flat() = stack_.forward(in.at("x")->flat()); }
  void backward(const TensorIn& in, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    MatrixRM gx;
    stack_.backward(in.at("x")->flat(), gout.at("y")->flat(), &gx);
    gin.at("x")->flat() = gx;
  }

 private:
  nn::DenseStack stack_;
};

// A node around two stacked Conv1dLayers.
class ConvNode final : public Node {
 public:
  ConvNode(int kernel, int stride) : kernel_(kernel), stride_(stride) {}
  ShapeMap setup(const ShapeMap& in, const NodeContext& ctx) override {
    const Shape x = in.at("x");
    first_ = nn::Conv1dLayer({x.rows, x.cols, kernel_, stride_}, 4, {nn::ActivationKind::LeakyRelu, 0.1f});
    second_ = nn::Conv1dLayer({first_.geometry().out_rows(), 4, kernel_, stride_}, 3, {nn::ActivationKind::Tanh});
    first_.create_weights(*this, "a_", ctx.seed);
    second_.create_weights(*this, "b_", ctx.seed + 1);
    return {{"y", {second_.geometry().out_rows(), 3}}};
  }
  void forward(const TensorIn& in, const TensorOut& out) override {
    const int batch = in.at("x")->batch();
    const MatrixRM& h = first_.forward(in.at("x")->flat(), batch);
    out.at("y")->flat() = second_.forward(h, batch);
  }
  void backward(const TensorIn& in, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    const int batch = in.at("x")->batch();
    MatrixRM gh, gx;
    second_.backward(gout.at("y")->flat(), batch, &gh);
    first_.backward(gh, batch, &gx);
    gin.at("x")->flat() = gx;
  }

 private:
  int kernel_, stride_;
  nn::Conv1dLayer first_, second_;
};

}  // namespace

TEST_CASE("linear layer: y = x w + b and its gradients", "[nn]") {
  const MatrixRM x = random_matrix(5, 3, 1), w = random_matrix(3, 4, 2), b = random_matrix(1, 4, 3);
  MatrixRM y(5, 4);
  nn::linear_forward(x, w, b, y);
  for (int r = 0; r < 5; ++r)
    for (int c = 0; c < 4; ++c) {
      float e = b(0, c);
      for (int k = 0; k < 3; ++k) e += x(r, k) * w(k, c);
      CHECK(y(r, c) == Approx(e));
    }
  const MatrixRM gy = random_matrix(5, 4, 4);
  MatrixRM gw = MatrixRM::Ones(3, 4), gb = MatrixRM::Ones(1, 4), gx(5, 3);
  nn::linear_backward_weights(x, gy, gw, gb);
  nn::linear_backward_input(w, gy, gx);
  CHECK(gw(1, 2) == Approx(1.0f + x.col(1).dot(gy.col(2))));  // accumulates
  CHECK(gb(0, 3) == Approx(1.0f + gy.col(3).sum()));
  CHECK(gx(4, 0) == Approx(gy.row(4).dot(w.row(0))));
  MatrixRM wrong(5, 5);
  CHECK_THROWS_AS(nn::linear_forward(x, w, b, wrong), Error);
}

TEST_CASE("gemm: every transpose combination, strided views, alpha and beta, both backends", "[nn]") {
  // Sizes on both sides of the BLAS threshold; the operands are blocks of
  // larger matrices, so that leading dimensions differ from the row lengths.
  for (const auto& [m, n, k] : std::vector<std::array<int, 3>>{{3, 4, 5}, {70, 48, 33}, {1, 300, 256}, {200, 1, 64}}) {
    const std::string backend = nn::gemm_backend(m, n, k);
    INFO("m " << m << ", n " << n << ", k " << k << ": " << backend);
    for (const bool ta : {false, true})
      for (const bool tb : {false, true}) {
        const MatrixRM big_a = random_matrix(ta ? k + 2 : m + 2, ta ? m + 3 : k + 3, 11);
        const MatrixRM big_b = random_matrix(tb ? n + 1 : k + 1, tb ? k + 4 : n + 4, 12);
        const auto a = big_a.block(1, 2, ta ? k : m, ta ? m : k);
        const auto b = big_b.block(1, 1, tb ? n : k, tb ? k : n);
        MatrixRM big_c = random_matrix(m + 2, n + 5, 13);
        const MatrixRM c0 = big_c.block(1, 3, m, n);
        auto c = big_c.block(1, 3, m, n);
        nn::gemm(ta ? nn::Op::Transpose : nn::Op::None, tb ? nn::Op::Transpose : nn::Op::None, 0.5f, a, b, 2.0f, c);
        Eigen::MatrixXd expected = 2.0 * c0.cast<double>();
        const Eigen::MatrixXd ad = ta ? Eigen::MatrixXd(a.cast<double>().transpose()) : Eigen::MatrixXd(a.cast<double>());
        const Eigen::MatrixXd bd = tb ? Eigen::MatrixXd(b.cast<double>().transpose()) : Eigen::MatrixXd(b.cast<double>());
        expected += 0.5 * ad * bd;
        INFO("transposes " << ta << tb);
        CHECK((c.cast<double>() - expected).cwiseAbs().maxCoeff() < 1e-4 * std::sqrt(double(k)));
        // Nothing outside the block is touched.
        CHECK(big_c.topRows(1) == random_matrix(m + 2, n + 5, 13).topRows(1));
        CHECK(big_c.leftCols(3) == random_matrix(m + 2, n + 5, 13).leftCols(3));
        // beta = 0 ignores what c held, NaN included.
        MatrixRM nan_c = MatrixRM::Constant(m, n, std::nanf(""));
        nn::gemm(ta ? nn::Op::Transpose : nn::Op::None, tb ? nn::Op::Transpose : nn::Op::None, 1.0f, a, b, 0.0f, nan_c);
        CHECK(nan_c.allFinite());
      }
  }
  MatrixRM c(3, 3);
  CHECK_THROWS_WITH(nn::gemm(nn::Op::None, nn::Op::None, 1.0f, random_matrix(3, 4, 1), random_matrix(5, 3, 2), 0.0f, c),
                    Catch::Contains("does not fit"));
}

TEST_CASE("activations and their derivatives from the output", "[nn]") {
  CHECK_THROWS_WITH(nn::parse_activation("gelu"), Catch::Contains("leaky_relu"));
  for (const auto& name : nn::activation_names()) CHECK(nn::to_string(nn::parse_activation(name)) == name);
  const float z0[6] = {-2.0f, -0.5f, -0.01f, 0.02f, 0.7f, 3.0f};
  for (const auto& name : nn::activation_names()) {
    const nn::Activation f{nn::parse_activation(name), 0.2f};
    MatrixRM y(1, 6), g = MatrixRM::Ones(1, 6);
    for (int i = 0; i < 6; ++i) y(0, i) = z0[i];
    nn::activate(f, y);
    nn::activation_backward(f, y, g);
    for (int i = 0; i < 6; ++i) {
      const float h = 1e-3f;
      MatrixRM p(1, 1), m(1, 1);
      p(0, 0) = z0[i] + h;
      m(0, 0) = z0[i] - h;
      nn::activate(f, p);
      nn::activate(f, m);
      INFO(name << " at " << z0[i]);
      CHECK(g(0, i) == Approx((p(0, 0) - m(0, 0)) / (2 * h)).epsilon(1e-2).margin(1e-3));
    }
    if (f.kind == nn::ActivationKind::LeakyRelu) CHECK(y(0, 0) == Approx(-0.4f));
    if (f.kind == nn::ActivationKind::Relu) CHECK(y(0, 1) == 0.0f);
  }
}

TEST_CASE("im2col and col2im are adjoint and follow the padding convention", "[nn]") {
  for (int kernel : {1, 2, 3, 5})
    for (int stride : {1, 2, 3})
      for (int rows : {1, 7, 12}) {
        const nn::Conv1dGeometry g{rows, 2, kernel, stride};
        CHECK(g.out_rows() == (rows + stride - 1) / stride);
        const MatrixRM x = random_matrix(rows, 2, 5), c = random_matrix(g.out_rows(), g.patch(), 6);
        MatrixRM cols(g.out_rows(), g.patch()), back = MatrixRM::Zero(rows, 2);
        nn::im2col(g, x, cols);
        nn::col2im_add(g, c, back);
        INFO("kernel " << kernel << " stride " << stride << " rows " << rows);
        CHECK(cols.cwiseProduct(c).sum() == Approx(x.cwiseProduct(back).sum()).epsilon(1e-5));
        // Output row o, tap j reads input row o*stride - (kernel-1)/2 + j.
        const int o = g.out_rows() - 1, j = kernel - 1, r = o * stride - (kernel - 1) / 2 + j;
        if (r < rows) CHECK(cols(o, j * 2 + 1) == x(r, 1));
        else CHECK(cols(o, j * 2 + 1) == 0.0f);
      }
}

TEST_CASE("dense stacks and conv layers backpropagate like finite differences", "[nn][gradcheck]") {
  StackNode stack({3, 7, 5, 2}, {nn::ActivationKind::LeakyRelu, 0.2f}, {nn::ActivationKind::Tanh});
  const GradCheckReport rs = check_node_gradients(stack, {{"x", random_tensor(2, 6, 3, 7)}}, {"s", 3});
  INFO(rs.str());
  CHECK(rs.entries.size() == 7);
  CHECK(rs.ok(1e-2));
  for (int stride : {1, 2, 3}) {
    ConvNode conv(3, stride);
    const GradCheckReport rc = check_node_gradients(conv, {{"x", random_tensor(3, 11, 2, 8)}}, {"c", 4});
    INFO("stride " << stride << "\n" << rc.str());
    CHECK(rc.entries.size() == 5);
    CHECK(rc.ok(1e-2));
  }
}

TEST_CASE("He initialisation has the requested spread and follows the seed", "[nn]") {
  CHECK(nn::he_std({nn::ActivationKind::Relu}, 50) == Approx(std::sqrt(2.0 / 50)));
  CHECK(nn::he_std({nn::ActivationKind::LeakyRelu, 0.5f}, 50) == Approx(std::sqrt(2.0 / 1.25 / 50)));
  CHECK(nn::he_std({nn::ActivationKind::None}, 50) == Approx(std::sqrt(1.0 / 50)));
  Tensor a(1, 100, 100), b(1, 100, 100), c(1, 100, 100);
  nn::fill_normal(a, 0.3f, 5);
  nn::fill_normal(b, 0.3f, 5);
  nn::fill_normal(c, 0.3f, nn::mix_seed(5, 1));
  CHECK(a.vec() == b.vec());
  CHECK(a.vec() != c.vec());
  const double mean = a.vec().mean();
  CHECK(std::abs(mean) < 0.01);
  CHECK(std::sqrt(a.vec().squaredNorm() / double(a.size())) == Approx(0.3).epsilon(0.03));
  CHECK(nn::mix_seed(5, 1) != nn::mix_seed(5, 2));
}

// The kernels nn::gemm uses first for a small weight matrix against a tall
// stack of vertex features: against double products, on strided blocks, with
// widths that end mid-vector and row counts that end mid-block.
TEST_CASE("skinny gemm: tall outputs and weight gradients match double products", "[nn]") {
  const MatrixRM probe_a = random_matrix(64, 8, 1), probe_b = random_matrix(8, 8, 2);
  MatrixRM probe_c(64, 8);
  if (!nn::detail::skinny_gemm(false, false, 1.0f, probe_a, probe_b, 0.0f, probe_c)) {
    WARN("skinny gemm skipped: this CPU has no AVX-512 (or DRAPE_PORTABLE_KERNELS is set); nn::gemm uses the BLAS");
    return;
  }
  struct Case {
    bool ta, tb;
    int m, n, k;
  };
  std::vector<Case> cases;
  for (const int n : {1, 3, 16, 17, 33, 64, 65, 130, 320})
    for (const int k : {1, 3, 15, 64, 160, 320}) {
      cases.push_back({false, false, 301, n, k});
      cases.push_back({false, true, 301, n, k});
    }
  for (const int m : {1, 3, 15, 25, 64, 320})
    for (const int n : {1, 3, 16, 50, 64, 320}) cases.push_back({true, false, m, n, 700});
  for (const Case& t : cases) {
    INFO("m " << t.m << ", n " << t.n << ", k " << t.k << ", transposes " << t.ta << t.tb);
    const MatrixRM big_a = random_matrix(t.ta ? t.k + 2 : t.m + 2, t.ta ? t.m + 3 : t.k + 3, 21);
    const MatrixRM big_b = random_matrix(t.tb ? t.n + 1 : t.k + 1, t.tb ? t.k + 4 : t.n + 4, 22);
    const auto a = big_a.block(1, 2, t.ta ? t.k : t.m, t.ta ? t.m : t.k);
    const auto b = big_b.block(1, 1, t.tb ? t.n : t.k, t.tb ? t.k : t.n);
    const Eigen::MatrixXd ad = t.ta ? Eigen::MatrixXd(a.cast<double>().transpose()) : Eigen::MatrixXd(a.cast<double>());
    const Eigen::MatrixXd bd = t.tb ? Eigen::MatrixXd(b.cast<double>().transpose()) : Eigen::MatrixXd(b.cast<double>());
    const Eigen::MatrixXd product = ad * bd;
    const double tolerance = 1e-5 * std::sqrt(double(t.k)) * (1.0 + product.cwiseAbs().maxCoeff());
    for (const float beta : {0.0f, 1.0f}) {
      MatrixRM big_c = random_matrix(t.m + 2, t.n + 5, 23);
      if (beta == 0.0f) big_c.block(1, 3, t.m, t.n).setConstant(std::nanf(""));  // beta = 0 never reads c
      const MatrixRM before = big_c;
      auto c = big_c.block(1, 3, t.m, t.n);
      REQUIRE(nn::detail::skinny_gemm(t.ta, t.tb, 1.0f, a, b, beta, c));
      const Eigen::MatrixXd expected =
          product + (beta == 1.0f ? Eigen::MatrixXd(before.block(1, 3, t.m, t.n).cast<double>()) : Eigen::MatrixXd::Zero(t.m, t.n));
      CHECK((c.cast<double>() - expected).cwiseAbs().maxCoeff() < tolerance);
      // Nothing outside the block is touched.
      CHECK(big_c.topRows(1) == before.topRows(1));
      CHECK(big_c.bottomRows(1) == before.bottomRows(1));
      CHECK(big_c.leftCols(3) == before.leftCols(3));
      CHECK(big_c.rightCols(2) == before.rightCols(2));
    }
  }
  // What it does not take is left to the caller, c untouched.
  MatrixRM c = MatrixRM::Constant(64, 8, 7.0f);
  CHECK_FALSE(nn::detail::skinny_gemm(false, false, 0.5f, probe_a, probe_b, 0.0f, c));
  CHECK_FALSE(nn::detail::skinny_gemm(false, false, 1.0f, probe_a, probe_b, 2.0f, c));
  CHECK_FALSE(nn::detail::skinny_gemm(true, true, 1.0f, random_matrix(8, 64, 3), random_matrix(8, 8, 4), 0.0f, c));
  CHECK_FALSE(nn::detail::skinny_gemm(false, false, 1.0f, random_matrix(64, 400, 5), random_matrix(400, 8, 6), 0.0f, c));
  CHECK((c.array() == 7.0f).all());
}
