// Learning-rate schedules give the documented values; the plateau and early
// stopping helpers react to validation losses as documented and resume exactly.
#include <catch2/catch.hpp>

#include <drape/training/schedule.hpp>

#include <cmath>

using namespace drape;

TEST_CASE("schedules follow their formulas", "[training][schedule]") {
  LrSchedule s;
  s.base = 0.1;
  SECTION("constant") {
    CHECK(s.at(0) == 0.1);
    CHECK(s.at(1000) == 0.1);
  }
  SECTION("step decay") {
    s.kind = LrSchedule::Kind::Step;
    s.gamma = 0.5;
    s.step_size = 3;
    CHECK(s.at(0) == Approx(0.1));
    CHECK(s.at(2) == Approx(0.1));
    CHECK(s.at(3) == Approx(0.05));
    CHECK(s.at(8) == Approx(0.025));
    CHECK(s.at(9) == Approx(0.0125));
  }
  SECTION("exponential") {
    s.kind = LrSchedule::Kind::Exponential;
    s.gamma = 0.9;
    CHECK(s.at(0) == Approx(0.1));
    CHECK(s.at(1) == Approx(0.09));
    CHECK(s.at(10) == Approx(0.1 * std::pow(0.9, 10)));
  }
  SECTION("cosine, then held at min_lr") {
    s.kind = LrSchedule::Kind::Cosine;
    s.total = 100;
    s.min_lr = 0.001;
    CHECK(s.at(0) == Approx(0.1));
    CHECK(s.at(50) == Approx(0.001 + 0.099 * 0.5));
    CHECK(s.at(25) == Approx(0.001 + 0.099 * 0.5 * (1.0 + std::cos(M_PI / 4))));
    CHECK(s.at(100) == Approx(0.001));
    CHECK(s.at(500) == Approx(0.001));
  }
  SECTION("linear warm-up before the schedule") {
    s.kind = LrSchedule::Kind::Step;
    s.gamma = 0.5;
    s.step_size = 2;
    s.warmup = 4;
    CHECK(s.at(0) == Approx(0.025));
    CHECK(s.at(3) == Approx(0.1));
    CHECK(s.at(4) == Approx(0.1));  // the schedule's epoch 0
    CHECK(s.at(6) == Approx(0.05));
  }
}

TEST_CASE("schedules read from YAML, with errors at file:line", "[training][schedule]") {
  const LrSchedule s = LrSchedule::from_yaml(YAML::Load("{ type: cosine, lr: 2.0e-3, total: 50, min_lr: 1.0e-5, warmup: 2 }"), "train.yaml");
  CHECK(s.kind == LrSchedule::Kind::Cosine);
  CHECK(s.base == 2e-3);
  CHECK(s.total == 50);
  CHECK(s.min_lr == 1e-5);
  CHECK(s.warmup == 2);
  CHECK(LrSchedule::from_yaml(YAML::Load("{}"), "t.yaml").kind == LrSchedule::Kind::Constant);
  CHECK_THROWS_AS(LrSchedule::from_yaml(YAML::Load("{ type: cosin }"), "t.yaml"), ConfigError);
  CHECK_THROWS_WITH(LrSchedule::from_yaml(YAML::Load("type: step\nstep_sise: 3\n"), "t.yaml"),
                    Catch::Contains("t.yaml:2") && Catch::Contains("step_size"));
  CHECK_THROWS_AS(LrSchedule::from_yaml(YAML::Load("{ gamma: 1.5 }"), "t.yaml"), ConfigError);
}

TEST_CASE("ReduceOnPlateau scales down after `patience` epochs without improvement", "[training][schedule]") {
  ReduceOnPlateau p({.factor = 0.5, .patience = 2, .threshold = 0.01, .cooldown = 1, .min_scale = 0.2});
  CHECK_FALSE(p.update(1.0));
  CHECK_FALSE(p.update(0.5));    // better
  CHECK_FALSE(p.update(0.499));  // within the relative threshold: not better (bad 1)
  CHECK_FALSE(p.update(0.6));    // bad 2
  CHECK(p.update(0.7));          // bad 3 > patience: reduce
  CHECK(p.scale() == 0.5);
  CHECK(p.best() == 0.5);
  const auto saved = p.state();
  CHECK_FALSE(p.update(0.7));  // cooldown epoch does not count
  CHECK_FALSE(p.update(0.7));
  CHECK_FALSE(p.update(0.7));
  CHECK(p.update(0.7));
  CHECK(p.scale() == 0.25);
  for (int i = 0; i < 10; ++i) p.update(0.7);
  CHECK(p.scale() == 0.2);  // floored at min_scale
  // Restoring the state repeats the same decisions.
  ReduceOnPlateau q({.factor = 0.5, .patience = 2, .threshold = 0.01, .cooldown = 1, .min_scale = 0.2});
  q.set_state(saved);
  CHECK(q.scale() == 0.5);
  CHECK_FALSE(q.update(0.7));
  CHECK_FALSE(q.update(0.7));
  CHECK_FALSE(q.update(0.7));
  CHECK(q.update(0.7));
  CHECK_THROWS_AS(q.set_state({{"scale", 1.0}}), ConfigError);
}

TEST_CASE("EarlyStopping stops after `patience` epochs without improvement and remembers the best", "[training][schedule]") {
  EarlyStopping e({.patience = 3, .min_delta = 0.01});
  CHECK_FALSE(e.update(1.0));
  CHECK(e.improved());
  CHECK_FALSE(e.update(0.8));
  CHECK(e.improved());
  CHECK_FALSE(e.update(0.795));  // not better by min_delta
  CHECK_FALSE(e.improved());
  CHECK_FALSE(e.update(0.9));
  const auto saved = e.state();
  CHECK(e.update(0.85));
  CHECK(e.best() == 0.8);
  CHECK(e.best_epoch() == 1);
  EarlyStopping f({.patience = 3, .min_delta = 0.01});
  f.set_state(saved);
  CHECK(f.update(0.85));
  CHECK(f.best_epoch() == 1);
}
