#pragma once
// Training a model as a user does it, the service behind `drape train` and
// the experiment runner's training rows: the output's lock (rank 0, which
// alone writes; output_lock.hpp), train() (trainer.hpp), then the training
// bodies' domain recorded in the model file (model_domain.hpp), after every
// run, so an interrupted model has it too.
#include <drape/training/model_domain.hpp>
#include <drape/training/trainer.hpp>

#include <optional>

namespace drape {

struct TrainedModel {
  TrainReport report;
  std::optional<ModelDomain> domain;  // recorded by rank 0; none on other ranks
};

TrainedModel train_model(const Registry& registry, const TrainOptions& options);

}  // namespace drape
