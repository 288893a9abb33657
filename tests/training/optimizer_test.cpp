// Adam and SGD minimise known functions, and their updates match the formulas.
#include <catch2/catch.hpp>

#include <drape/training/optimizer.hpp>

#include <cmath>

using namespace drape;

namespace {

// Parameters of a test function held in one weight [1, 1, n].
struct Problem {
  Weight w;
  explicit Problem(std::vector<float> start) {
    w.value = Tensor(1, 1, static_cast<int>(start.size()));
    w.grad = Tensor(1, 1, static_cast<int>(start.size()));
    std::copy(start.begin(), start.end(), w.value.data());
  }
  NamedWeights named() { return {{"f/x", &w}}; }
  float x(int i) const { return w.value.data()[i]; }
};

// f(x) = sum_i c_i (x_i - t_i)^2, an ill-conditioned quadratic (c from 1 to 100).
double quadratic(Problem& p) {
  const float c[3] = {1.0f, 10.0f, 100.0f}, t[3] = {3.0f, -2.0f, 0.5f};
  double f = 0.0;
  for (int i = 0; i < 3; ++i) {
    const float d = p.x(i) - t[i];
    f += c[i] * d * d;
    p.w.grad.data()[i] = 2.0f * c[i] * d;
  }
  return f;
}

// A Rosenbrock valley f = (1 - x)^2 + 20 (y - x^2)^2, minimum 0 at (1, 1).
double rosenbrock(Problem& p) {
  const double x = p.x(0), y = p.x(1);
  p.w.grad.data()[0] = static_cast<float>(-2.0 * (1.0 - x) - 80.0 * x * (y - x * x));
  p.w.grad.data()[1] = static_cast<float>(40.0 * (y - x * x));
  return (1.0 - x) * (1.0 - x) + 20.0 * (y - x * x) * (y - x * x);
}

template <class Opt>
double minimise(Problem& p, Opt& opt, double (*f)(Problem&), const LrSchedule& lr, long steps) {
  for (long s = 0; s < steps; ++s) {
    p.w.grad.set_zero();
    f(p);
    opt.step(lr.at(s));
  }
  p.w.grad.set_zero();
  return f(p);
}

}  // namespace

TEST_CASE("Adam minimises an ill-conditioned quadratic", "[training][optimizer]") {
  Problem p({0.0f, 0.0f, 0.0f});
  Adam adam(p.named());
  const double start = quadratic(p);
  LrSchedule lr;
  lr.kind = LrSchedule::Kind::Cosine;
  lr.base = 0.1;
  lr.total = 2000;
  const double end = minimise(p, adam, quadratic, lr, 2000);
  CHECK(end < 1e-6 * start);
  CHECK(p.x(0) == Approx(3.0f).margin(1e-3));
  CHECK(p.x(1) == Approx(-2.0f).margin(1e-3));
  CHECK(p.x(2) == Approx(0.5f).margin(1e-3));
  CHECK(adam.steps() == 2000);
}

TEST_CASE("Adam finds the minimum of a Rosenbrock valley", "[training][optimizer]") {
  Problem p({-1.2f, 1.0f});
  Adam adam(p.named());
  LrSchedule lr;
  lr.kind = LrSchedule::Kind::Cosine;
  lr.base = 0.02;
  lr.total = 6000;
  const double end = minimise(p, adam, rosenbrock, lr, 6000);
  CHECK(end < 1e-6);
  CHECK(p.x(0) == Approx(1.0f).margin(2e-3));
  CHECK(p.x(1) == Approx(1.0f).margin(4e-3));
}

TEST_CASE("SGD with momentum minimises the quadratic and the valley", "[training][optimizer]") {
  LrSchedule lr;
  lr.base = 0.004;  // stable for the largest curvature 2 * 100 with momentum 0.9
  SECTION("quadratic, heavy ball beats plain SGD") {
    Problem plain({0.0f, 0.0f, 0.0f}), heavy({0.0f, 0.0f, 0.0f}), nesterov({0.0f, 0.0f, 0.0f});
    SGD a(plain.named()), b(heavy.named(), {.momentum = 0.9}), c(nesterov.named(), {.momentum = 0.9, .nesterov = true});
    const double fa = minimise(plain, a, quadratic, lr, 300);
    const double fb = minimise(heavy, b, quadratic, lr, 300);
    const double fc = minimise(nesterov, c, quadratic, lr, 300);
    CHECK(fb < 1e-8);
    CHECK(fc < 1e-8);
    CHECK(fa > 1e-3);  // the flat direction (c = 1) is slow without momentum
    CHECK(heavy.x(0) == Approx(3.0f).margin(1e-4));
  }
  SECTION("Rosenbrock") {
    Problem p({-1.2f, 1.0f});
    SGD sgd(p.named(), {.momentum = 0.9});
    lr.base = 1e-3;
    CHECK(minimise(p, sgd, rosenbrock, lr, 20000) < 1e-6);
    CHECK(p.x(0) == Approx(1.0f).margin(2e-3));
  }
}

TEST_CASE("optimizer updates follow the formulas", "[training][optimizer]") {
  SECTION("Adam's first step moves every weight by lr (bias corrected)") {
    Problem p({1.0f, -2.0f, 0.5f});
    p.w.grad.data()[0] = 0.3f;
    p.w.grad.data()[1] = -40.0f;
    p.w.grad.data()[2] = 1e-3f;
    Adam adam(p.named(), {.epsilon = 0.0});
    adam.step(0.01);
    CHECK(p.x(0) == Approx(0.99f).epsilon(1e-6));
    CHECK(p.x(1) == Approx(-1.99f).epsilon(1e-6));
    CHECK(p.x(2) == Approx(0.49f).epsilon(1e-6));
  }
  SECTION("Adam without bias correction takes a (1 - b1) / sqrt(1 - b2) sized first step") {
    Problem p({0.0f});
    p.w.grad.data()[0] = 2.0f;
    Adam adam(p.named(), {.epsilon = 0.0, .bias_correction = false});
    adam.step(0.01);
    CHECK(p.x(0) == Approx(-0.01 * 0.1 / std::sqrt(0.001)).epsilon(1e-5));
  }
  SECTION("decoupled weight decay shrinks the weight by lr * wd, independent of the gradient") {
    Problem p({2.0f});
    Adam adam(p.named(), {.epsilon = 1.0, .weight_decay = 0.5});  // zero gradient: only decay acts
    adam.step(0.1);
    CHECK(p.x(0) == Approx(2.0f * (1.0f - 0.05f)));
  }
  SECTION("SGD momentum accumulates velocity") {
    Problem p({0.0f});
    SGD sgd(p.named(), {.momentum = 0.5});
    for (int s = 0; s < 3; ++s) {
      p.w.grad.data()[0] = 1.0f;
      sgd.step(0.1);
    }
    // Velocities 1, 1.5, 1.75: x = -0.1 * 4.25.
    CHECK(p.x(0) == Approx(-0.425f));
  }
}

TEST_CASE("optimizer state restores an identical trajectory", "[training][optimizer]") {
  for (const bool use_adam : {true, false}) {
    Problem a({-1.2f, 1.0f}), b({-1.2f, 1.0f});
    std::unique_ptr<Optimizer> oa, ob;
    if (use_adam) {
      oa = std::make_unique<Adam>(a.named(), AdamOptions{.weight_decay = 0.01});
      ob = std::make_unique<Adam>(b.named(), AdamOptions{.weight_decay = 0.01});
    } else {
      oa = std::make_unique<SGD>(a.named(), SgdOptions{.momentum = 0.9});
      ob = std::make_unique<SGD>(b.named(), SgdOptions{.momentum = 0.9});
    }
    for (int s = 0; s < 10; ++s) {
      rosenbrock(a);
      oa->step(1e-3);
    }
    // b takes over a's weights and state, then both continue.
    b.w.value = a.w.value;
    ob->set_state(oa->state());
    for (int s = 0; s < 10; ++s) {
      rosenbrock(a);
      oa->step(1e-3);
      rosenbrock(b);
      ob->step(1e-3);
    }
    CHECK(a.x(0) == b.x(0));
    CHECK(a.x(1) == b.x(1));
    CHECK(ob->steps() == 20);
  }
}

TEST_CASE("gradient clipping bounds the joint norm", "[training][optimizer]") {
  Problem p({0.0f, 0.0f});
  Weight other;
  other.value = Tensor(1, 1, 1);
  other.grad = Tensor(1, 1, 1, 12.0f);
  p.w.grad.data()[0] = 3.0f;
  p.w.grad.data()[1] = 4.0f;
  const NamedWeights all = {{"a", &p.w}, {"b", &other}};
  CHECK(grad_norm(all) == Approx(13.0));
  CHECK(clip_grad_norm(all, 1.3) == Approx(13.0));
  CHECK(grad_norm(all) == Approx(1.3));
  CHECK(other.grad.data()[0] == Approx(1.2f));
  CHECK(clip_grad_norm(all, 100.0) == Approx(1.3));  // below the bound: unchanged
  CHECK(other.grad.data()[0] == Approx(1.2f));
}
