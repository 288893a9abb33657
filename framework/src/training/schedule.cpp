#include <drape/errors.hpp>
#include <drape/params.hpp>
#include <drape/training/schedule.hpp>

#include <algorithm>
#include <cmath>

namespace drape {

const char* to_string(LrSchedule::Kind kind) {
  switch (kind) {
    case LrSchedule::Kind::Constant: return "constant";
    case LrSchedule::Kind::Step: return "step";
    case LrSchedule::Kind::Cosine: return "cosine";
    case LrSchedule::Kind::Exponential: return "exponential";
  }
  return "?";
}

double LrSchedule::at(long epoch) const {
  if (epoch < 0) epoch = 0;
  if (epoch < warmup) return base * static_cast<double>(epoch + 1) / static_cast<double>(warmup);
  const long t = epoch - warmup;
  switch (kind) {
    case Kind::Constant: return base;
    case Kind::Step: return base * std::pow(gamma, static_cast<double>(t / std::max(1L, step_size)));
    case Kind::Exponential: return base * std::pow(gamma, static_cast<double>(t));
    case Kind::Cosine: {
      const double progress = static_cast<double>(std::min(t, total)) / static_cast<double>(std::max(1L, total));
      return min_lr + (base - min_lr) * 0.5 * (1.0 + std::cos(M_PI * progress));
    }
  }
  return base;
}

LrSchedule LrSchedule::from_yaml(const YAML::Node& node, const std::string& file) {
  const std::vector<ParamSpec> specs = {
      {.name = "type", .type = ParamType::String, .default_value = "constant",
       .doc = "schedule", .choices = {"constant", "step", "cosine", "exponential"}},
      {.name = "lr", .type = ParamType::Float, .default_value = "1.0e-3",
       .doc = "base learning rate", .min = 0.0},
      {.name = "gamma", .type = ParamType::Float, .default_value = "0.1",
       .doc = "decay factor (step: per step_size epochs, exponential: per epoch)", .min = 0.0, .max = 1.0},
      {.name = "step_size", .type = ParamType::Int, .default_value = "10",
       .doc = "epochs between step decays", .min = 1.0},
      {.name = "total", .type = ParamType::Int, .default_value = "100",
       .doc = "cosine: epochs from lr to min_lr", .min = 1.0},
      {.name = "min_lr", .type = ParamType::Float, .default_value = "0.0",
       .doc = "cosine: final learning rate", .min = 0.0},
      {.name = "warmup", .type = ParamType::Int, .default_value = "0",
       .doc = "epochs of linear warm-up", .min = 0.0},
  };
  const Params p(specs, param_values_from_yaml(node, file), "learning-rate schedule");
  LrSchedule s;
  const std::string type = p.get_string("type");
  s.kind = type == "step" ? Kind::Step : type == "cosine" ? Kind::Cosine : type == "exponential" ? Kind::Exponential : Kind::Constant;
  s.base = p.get_float("lr");
  s.gamma = p.get_float("gamma");
  s.step_size = p.get_int("step_size");
  s.total = p.get_int("total");
  s.min_lr = p.get_float("min_lr");
  s.warmup = p.get_int("warmup");
  return s;
}

namespace {

double get(const std::map<std::string, double>& state, const std::string& key, const char* owner) {
  const auto it = state.find(key);
  if (it == state.end()) throw ConfigError(std::string(owner) + " state: missing '" + key + "'");
  return it->second;
}

}  // namespace

bool ReduceOnPlateau::update(double loss) {
  const double margin = options_.threshold * std::abs(best_);
  if (loss < best_ - (std::isfinite(margin) ? margin : 0.0)) {
    best_ = loss;
    bad_epochs_ = 0;
  } else {
    ++bad_epochs_;
  }
  if (cooldown_left_ > 0) {
    --cooldown_left_;
    bad_epochs_ = 0;
  }
  if (bad_epochs_ > options_.patience) {
    const double reduced = std::max(scale_ * options_.factor, options_.min_scale);
    bad_epochs_ = 0;
    cooldown_left_ = options_.cooldown;
    if (reduced < scale_) {
      scale_ = reduced;
      return true;
    }
  }
  return false;
}

std::map<std::string, double> ReduceOnPlateau::state() const {
  return {{"scale", scale_}, {"best", best_}, {"bad_epochs", bad_epochs_}, {"cooldown_left", cooldown_left_}};
}

void ReduceOnPlateau::set_state(const std::map<std::string, double>& state) {
  scale_ = get(state, "scale", "plateau");
  best_ = get(state, "best", "plateau");
  bad_epochs_ = static_cast<int>(get(state, "bad_epochs", "plateau"));
  cooldown_left_ = static_cast<int>(get(state, "cooldown_left", "plateau"));
}

bool EarlyStopping::update(double loss) {
  improved_ = loss < best_ - options_.min_delta;
  if (improved_) {
    best_ = loss;
    best_epoch_ = epochs_;
    bad_epochs_ = 0;
  } else {
    ++bad_epochs_;
  }
  ++epochs_;
  return bad_epochs_ >= options_.patience;
}

std::map<std::string, double> EarlyStopping::state() const {
  return {{"best", best_}, {"best_epoch", static_cast<double>(best_epoch_)}, {"epochs", static_cast<double>(epochs_)},
          {"bad_epochs", bad_epochs_}};
}

void EarlyStopping::set_state(const std::map<std::string, double>& state) {
  best_ = get(state, "best", "early stopping");
  best_epoch_ = static_cast<long>(get(state, "best_epoch", "early stopping"));
  epochs_ = static_cast<long>(get(state, "epochs", "early stopping"));
  bad_epochs_ = static_cast<int>(get(state, "bad_epochs", "early stopping"));
  improved_ = false;
}

}  // namespace drape
