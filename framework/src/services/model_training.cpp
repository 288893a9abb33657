// train_model (services/model_training.hpp).
#include <drape/training/distributed.hpp>
#include <drape/io/output_lock.hpp>
#include <drape/services/model_training.hpp>

#include <memory>

namespace drape {

TrainedModel train_model(const Registry& registry, const TrainOptions& options) {
  const bool writer = !options.ranks || options.ranks->rank() == 0;
  // Before the trainer looks at the output.
  std::unique_ptr<OutputLock> lock;
  if (writer) lock = std::make_unique<OutputLock>(options.out, "drape train", true);
  TrainedModel out;
  out.report = train(registry, options);
  if (writer) out.domain = record_model_domain(registry, options.out, options.data, options.out, options.train_fraction);
  return out;
}

}  // namespace drape
