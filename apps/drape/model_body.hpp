#pragma once
// The model and the body a model-driven command works on: `--model FILE` or
// the shipped model, and `--body FILE` (a mesh in the model's body topology)
// or `--bmi X [--height H --sex S --girth name=value ...]` (made by the
// model's body plugin). Shared by predict, optimize, render and the
// benchmarks.
#include "command.hpp"

#include <drape/model.hpp>
#include <drape/model_domain.hpp>

namespace drape::cli {

// Declares the options model_body reads: --body, --bmi, --height, --sex,
// --girth, --strict and --garment-size (`body_help` says what --body is in
// this command), so every model-driven command takes the same body options.
void add_model_body_options(po::options_description& options, const std::string& body_help);

// One sample. ConfigError for a mesh of the wrong vertex count, or a mesh
// given to a graph that takes body parameters. A model trained on several
// garment sizes also gets --garment-size.
// A body given away from where the model's training bodies stood (lifted,
// or centred elsewhere: model_domain.hpp's placement) is moved there, with a
// note; *moved_by (when given) is what to add to the outputs to move them
// back with the body (zero when it was not moved).
SampleBatch model_body(const Model& model, const po::variables_map& vm, Eigen::RowVector3d* moved_by = nullptr);

// The move itself: translates batch's one body to the training bodies'
// placement when the domain (the model's, read_domain) records it and the
// body stands outside it; returns what to add to outputs to move them back
// (zero: not moved).
Eigen::RowVector3d place_like_training(const Model& model, const std::optional<ModelDomain>& domain, SampleBatch& batch);

// Warns on stderr, naming the measure and the trained range, when the body
// lies outside the model's training domain (`domain`, read_domain of the
// model file: model_domain.hpp); with strict (the commands' --strict) a
// ConfigError instead, so the command exits 2.
// model_body calls it, reading --strict from vm.
void check_domain(const Model& model, const std::optional<ModelDomain>& domain, const SampleBatch& batch, bool strict);

// A note on stderr when the model's garment (one size) is smaller around than
// the body by the tailor's rule (garment_size.hpp): what the model predicts for
// such a body is that garment riding up or stretched, as it was simulated.
// model_body calls it.
void note_fit(const Model& model, const SampleBatch& batch);

// --model, or the shipped pretrained model (default_model_path); UsageError when neither exists.
std::string model_file_or_default(const po::variables_map& vm);

}  // namespace drape::cli
