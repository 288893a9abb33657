#pragma once
// The model and the body a model-driven command works on: `--model FILE` or
// the shipped model, and `--body FILE` (a mesh in the model's body topology)
// or `--bmi X [--height H --sex S --girth name=value ...]` (made by the
// model's body plugin). Shared by predict, optimize, render and the
// benchmarks.
#include "command.hpp"

#include <drape/geometry/body_heading.hpp>
#include <drape/io/dataset.hpp>
#include <drape/registry.hpp>
#include <drape/training/model.hpp>
#include <drape/training/model_domain.hpp>

namespace drape::cli {

// Declares the options model_body reads: --body, --bmi, --height, --sex,
// --girth, --strict and --garment-size (`body_help` says what --body is in
// this command), so every model-driven command takes the same body options.
void add_model_body_options(po::options_description& options, const std::string& body_help);

// One sample from --body FILE or --bmi ... (services/model_body.hpp's
// model_body_batch), made ready by prepare_bodies: a body given away from
// where the model's training bodies stood is moved there, and one facing
// another way turned to face as they did, with a note; *moved_by (when given)
// moves the outputs back with the body (BodyMove::back). Its notes and warnings go to stderr;
// --strict makes a body outside the training domain exit 2. `printed` (when
// given) receives the lines printed, for a picture to show them too.
// `fallback_pose` (optional): the pose the command takes from elsewhere when
// none of --pose, --pose-file and --smpl-theta is given (optimize: its
// scene's `body: pose:`), with `fallback_source` naming it in the note and in
// a refusal; a body mesh given posed keeps its own pose (said).
// `announce` false: the notes and warnings about the prediction (its size,
// the domain) are neither printed nor returned, for a command that draws a
// garment it was given rather than one it predicts (render --garment);
// refusals (--strict, a body it cannot take) still throw.
SampleBatch model_body(const Model& model, const po::variables_map& vm, BodyMove* moved_by = nullptr,
                       std::vector<std::string>* printed = nullptr, const Pose* fallback_pose = nullptr,
                       const std::string& fallback_source = "", bool refuse_crossing = false, bool announce = true);

// The pattern the batch's first body wears: the material space (a mesh with
// UVs) of the size chart's size of the grade it was fed, for a model of drapes
// in each body's own size; else the model's template. Its UVs are what a
// garment file written for that body carries (as simulate writes the size
// worn), and what the garment's strain is measured against.
const Mesh& worn_pattern(const Model& model, const SampleBatch& batch);

// The body asked for in words, for a picture's title: "BMI 30, 1.60 m, sex 0,
// posed shoulder_abduction=40, size large" (--bmi and what goes with it), or
// the --body file.
std::string asked_body_words(const po::variables_map& vm);

// The shipped model of posed drapes, beside the A-pose one in models/: the
// human rig's, as the A-pose default is (since 2026-12-02; the mannequin's
// is models/tshirt-coarse-posed.h5).
inline constexpr const char* posed_model_name = "tshirt-coarse-posed-human.h5";

// Whether --pose, --pose-file or --smpl-theta is given.
bool pose_given(const po::variables_map& vm);

// --model, or the shipped pretrained model: for a posed body (pose_given, or
// a --body mesh given posed: its limbs turned as limb_turns.hpp tells) the
// model of posed drapes (posed_model_name) when it is shipped and DRAPE_MODEL
// is not set, else default_model_path's; UsageError when none exists.
// posed_elsewhere: the body is posed by something other than these options
// (optimize's scene), and goes to the model of posed drapes too.
std::string model_file_or_default(const po::variables_map& vm, bool posed_elsewhere = false);

// Without --model (and DRAPE_MODEL unset): the shipped twin of `file` on the
// other rig when that one drapes bodies of `body_vertices` and `file` does not
// (said on stderr, naming `what` holds such bodies); else `file`. Reads the
// models' metadata, not their weights.
std::string model_file_for_rig(const po::variables_map& vm, const Registry& registry, const std::string& file,
                               Eigen::Index body_vertices, const std::string& what);

// With --body and without --model (and DRAPE_MODEL unset): the shipped
// model of the body mesh's rig, by its vertex count, as model_file_for_rig
// (a mannequin body went to the human rig's model and was refused by its
// count, where --bmi on a mannequin scene found the mannequin's model); a
// posed body of that rig goes to its model of posed drapes. Else `file`.
std::string model_file_for_body(const po::variables_map& vm, const Registry& registry, const std::string& file);

// model_file_or_default for a dataset's samples: without --model (and with
// DRAPE_MODEL unset), the shipped model of posed drapes when the default
// model drapes the A-pose only and one of `indices` is posed (said on
// stderr; the A-pose model drew a posed held-out set's bodies torn), then
// model_file_for_rig for the dataset's bodies.
std::string model_file_for_samples(const po::variables_map& vm, const Registry& registry, const DatasetReader& data,
                                   const std::vector<std::size_t>& indices);

}  // namespace drape::cli
