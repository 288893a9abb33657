#pragma once
// The body a scene drapes, made ready for Simulation::run: the service behind
// `drape simulate` and `drape.simulate`, so both drape the same body the same
// way. It checks a given body (vertex count, units), places it where and as
// the body model's bodies stand (a body morphs from the mean shape, which
// stands there facing +z: a body lifted or centred by another tool would drag
// the garment through the air, one turned about would morph through it;
// body_heading.hpp), and with `size: auto` picks the size the body's girth needs
// (garment_size.hpp). drape_scene_body runs it and moves the drape back.
#include <drape/geometry/body_heading.hpp>
#include <drape/scene/garment_size.hpp>
#include <drape/scene/simulation.hpp>

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace drape {

// m: how far from the mean body's placement (mean x and z of the vertices,
// lowest y) a body of the body model may stand (the shipped model's 1,600
// training bodies: within 4.2 mm in z, exactly in x and y).
inline constexpr double kBodyModelPlacementSpread = 0.01;

struct SceneBody {
  const Simulation* simulation = nullptr;  // what drapes it: with size: auto, the size it wears
  Eigen::MatrixX3d vertices;               // the target body, standing where the body model's bodies stand
  // Moves the drape (garment and body) back where, and as, the given body
  // stood (BodyMove::back); the identity when it was not moved.
  BodyMove moved_by;
  std::optional<SizeChoice> size;  // with size: auto, the choice and its measurements
  std::optional<GradeChoice> grade;  // with grade: auto, the grade and its measure
  // A posed body (docs/poses.md): `vertices` is `unposed` in `pose`. The
  // size is chosen on the unposed body (a raised arm is no girth).
  Pose pose;
  Eigen::MatrixX3d unposed;
  // For the user, one sentence each without a prefix: "the body stands ... m
  // from where ...; draped there and ...". The CLI prints them as "note: ...",
  // Python as warnings.
  std::vector<std::string> notes;
};

// A given body's vertices (`name` names it in messages: a file, or an
// argument). ConfigError for the wrong vertex count (saying the expected one),
// non-finite coordinates, other units or a body lying down (body_units.hpp),
// and, with size: auto, a body no size fits.
// The body is posed in `pose`, or in the scene's pose (`body: {pose: ...}`)
// when null: a given body is taken as unposed (the body model's A-pose);
// ConfigError when the model has no skeleton or the pose makes the body pass
// through itself (posed_body.hpp). A body given posed (its limbs turned,
// limb_turns.hpp) is unposed and posed in the pose read off it
// (unpose_given_body, given_body.hpp), the scene's pose giving way;
// ConfigError when `pose` is given too. A mesh the body model's faces read
// wrong is refused as predict refuses it (require_body_model_mesh: vertices
// in another order, a spike, mirrored; with `faces`, the file's own, faces
// that are not the model's), before anything is measured or simulated.
SceneBody scene_body(const SceneSimulations& simulations, const Eigen::MatrixX3d& given, const std::string& name,
                     const Pose* pose = nullptr, const Eigen::MatrixX3i* faces = nullptr);
// A body of the scene's body model: the scene's target request, changed by
// the caller (a BMI, girths).
SceneBody scene_body(const SceneSimulations& simulations, const BodyRequest& request, const std::string& name,
                     const Pose* pose = nullptr);

// Simulation::run on the prepared body; the result's garment and body are
// moved back by moved_by (where the given body stood). Options'
// start_garment and start_body are in the given body's frame too.
// When the scene's garment is smaller around than the mean body it is
// dressed on (a negative ease there): one clause saying so, with the loop,
// the body's girth and the grade that gives it its design ease; empty
// otherwise. drape_scene_body adds it to the contact's refusal of such a
// start, which comes before the first step.
std::string start_fit_hint(const Simulation& design);

SimulationResult drape_scene_body(const SceneBody& body, SimulationOptions options = {});

}  // namespace drape
