#pragma once
// The bodies a trained model drapes, made ready for Model::predict: the
// service behind `drape predict`/`optimize`/`render` and drape.Model.predict/
// optimize, so the command line and Python check, place and warn alike.
//  - model_body_batch: one body from a mesh (vertex count, units, a graph that
//    needs body parameters) or from the model's body plugin (a BodyRequest),
//    with the garment size of a model trained on several.
//  - prepare_bodies: per body of a batch, moves a body standing away from
//    where the training bodies stood there (model_domain.hpp, placement),
//    checks the training domain, and notes a garment too small around for it
//    (garment_size.hpp's tailor's rule). What it has to say comes back as
//    notices, for the face to print (CLI: "note: ..." on stderr) or warn
//    (Python warnings).
#include <drape/training/model.hpp>
#include <drape/training/model_domain.hpp>

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace drape {

struct Notice {
  enum class Level { note, warning };
  Level level = Level::note;
  std::string text;  // one sentence, without a "note: " prefix
};

struct ModelBodyInput {
  std::optional<Eigen::MatrixX3d> vertices;  // a body mesh in the model's body topology, or
  std::optional<BodyRequest> request;        // a body of the model's own body plugin
  std::string name = "body";                 // names a given mesh in messages (its file)
  std::optional<std::string> garment_size;   // for a model trained on several sizes
};

// A batch of one. ConfigError for a mesh of the wrong vertex count (saying the
// expected one), in other units, given to a graph that takes body parameters,
// and for a model of several sizes without a garment size.
SampleBatch model_body_batch(const Model& model, const ModelBodyInput& input);

struct PreparedBodies {
  // Per body: added to what the model predicts for it to move it back where
  // the body stood (zero when it was not moved).
  std::vector<Eigen::RowVector3d> moved_by;
  std::vector<Notice> notices;
};

// `domain`: the model file's (read_domain), none for a model that records
// none. With strict, a body outside the domain (or a model without one) is a
// ConfigError starting "<strict_option>: " instead of a warning.
PreparedBodies prepare_bodies(const Model& model, const std::optional<ModelDomain>& domain, SampleBatch& batch,
                              bool strict, const std::string& strict_option = "--strict");

}  // namespace drape
