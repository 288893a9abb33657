#pragma once
// Learning-rate schedules (a function of the epoch) and the two validation-
// driven helpers: ReduceOnPlateau scales the rate down when the validation loss
// stalls, EarlyStopping says when to stop. Both keep their state as numbers so a
// checkpoint can store them and a resumed run continues exactly.
#include <drape/errors.hpp>

#include <yaml-cpp/yaml.h>

#include <limits>
#include <map>
#include <string>

namespace drape {

struct LrSchedule {
  enum class Kind { Constant, Step, Cosine, Exponential };
  Kind kind = Kind::Constant;
  double base = 1e-3;   // the rate at the first epoch after warm-up
  double gamma = 0.1;   // step: factor every step_size epochs; exponential: factor per epoch
  long step_size = 10;  // step only
  long total = 100;     // cosine: epochs (after warm-up) to go from base to min_lr
  double min_lr = 0.0;  // cosine only
  long warmup = 0;      // epochs of linear ramp base*(e+1)/warmup before the schedule starts

  // After warm-up, with t = epoch - warmup:
  //   constant     base
  //   step         base * gamma^floor(t / step_size)
  //   exponential  base * gamma^t
  //   cosine       min_lr + (base - min_lr) * (1 + cos(pi * min(t, total) / total)) / 2
  double at(long epoch) const;

  // From YAML such as { type: cosine, lr: 1.0e-3, total: 200, min_lr: 1.0e-5, warmup: 5 };
  // unknown keys and bad values throw ConfigError with file:line.
  static LrSchedule from_yaml(const YAML::Node& node, const std::string& file);
};
const char* to_string(LrSchedule::Kind kind);

class ReduceOnPlateau {
 public:
  struct Options {
    double factor = 0.1;      // scale *= factor on a plateau
    int patience = 10;        // epochs without improvement tolerated
    double threshold = 1e-4;  // relative: better means loss < best * (1 - threshold) (for positive losses)
    int cooldown = 0;         // epochs after a reduction before counting again
    double min_scale = 0.0;
  };
  ReduceOnPlateau() = default;
  explicit ReduceOnPlateau(const Options& options) : options_(options) {}
  // Feeds one validation loss; true when the scale was reduced by this call.
  bool update(double loss);
  double scale() const { return scale_; }  // multiply the schedule's rate by it
  double best() const { return best_; }

  std::map<std::string, double> state() const;
  void set_state(const std::map<std::string, double>& state);

 private:
  Options options_;
  double scale_ = 1.0;
  double best_ = std::numeric_limits<double>::infinity();
  int bad_epochs_ = 0;
  int cooldown_left_ = 0;
};

class EarlyStopping {
 public:
  struct Options {
    int patience = 20;       // stop after this many epochs without improvement
    double min_delta = 0.0;  // absolute improvement that counts
  };
  EarlyStopping() = default;
  explicit EarlyStopping(const Options& options) : options_(options) {}
  // Feeds one validation loss; true when training should stop.
  bool update(double loss);
  bool improved() const { return improved_; }  // the last loss was a new best (save the model)
  double best() const { return best_; }
  long best_epoch() const { return best_epoch_; }  // index of the best update, counting from 0

  std::map<std::string, double> state() const;
  void set_state(const std::map<std::string, double>& state);

 private:
  Options options_;
  double best_ = std::numeric_limits<double>::infinity();
  long best_epoch_ = -1;
  long epochs_ = 0;
  int bad_epochs_ = 0;
  bool improved_ = false;
};

}  // namespace drape
