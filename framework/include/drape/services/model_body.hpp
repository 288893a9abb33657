#pragma once
// The bodies a trained model drapes, made ready for Model::predict: the
// service behind `drape predict`/`optimize`/`render` and drape.Model.predict/
// optimize, so the command line and Python check, place and warn alike.
//  - model_body_batch: one body from a mesh (vertex count, units, a graph that
//    needs body parameters) or from the model's body plugin (a BodyRequest),
//    with the garment size of a model trained on several.
//  - BodyPreparation::prepare: per body of a batch, turns a body facing another
//    way to face as the model's bodies face (body_heading.hpp) and moves a body
//    standing away from where the training bodies stood there (model_domain.hpp, placement),
//    checks the training domain, reads the pose off a body mesh given posed
//    to a model of posed drapes (pose_fit.hpp) and unposes it, and notes a garment too small around for it
//    (garment_size.hpp's tailor's rule); for a model of drapes in each body's
//    own size, chooses the size by that rule unless the caller named one. What it has to say comes back as
//    notices, for the face to print (CLI: "note: ..." on stderr) or warn
//    (Python warnings).
#include <drape/bodies/given_body.hpp>
#include <drape/training/model.hpp>
#include <drape/training/model_domain.hpp>
#include <drape/scene/size_table.hpp>

#include <Eigen/Core>
#include <array>
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
  std::optional<Eigen::MatrixX3i> faces;     // (with vertices, when the file had them: checked against the model's)
  std::optional<BodyRequest> request;        // a body of the model's own body plugin
  std::string name = "body";                 // names a given mesh in messages (its file)
  // For a model trained on several sizes (input garment_size: a size name),
  // or on drapes in each body's own size (input garment_grade: a size name of
  // its size chart, or "auto", the default: BodyPreparation::prepare chooses
  // by the tailor's rule).
  std::optional<std::string> garment_size;
  std::optional<double> garment_grade;  // input garment_grade: a grade given as a number instead
};

// Poses the (prepared, unposed) bodies of `batch` for a model that drapes
// posed bodies (its graph takes unposed_body, joint_transforms or pose;
// docs/poses.md): each body becomes `pose` (angles it does not set at the
// body's rest angles), its rest mesh unposed_body. Run after
// BodyPreparation::prepare, which measures and places the unposed body (a
// raised arm is no girth), and posing commutes with its move. An empty pose
// leaves an A-pose model's batch alone; a pose for a model of A-pose bodies
// is a ConfigError (its drapes would be silently wrong).
void pose_model_batch(const Model& model, SampleBatch& batch, const Pose& pose);
// The same with a pose per body (`poses`, one per body of the batch).
void pose_model_batch(const Model& model, SampleBatch& batch, const std::vector<Pose>& poses);
// True for a model whose graph takes the posing inputs.
bool model_takes_pose(const Model& model);

// The grades a model taking garment_grade accepts (a grade is the garment's
// girth over its design size's).
inline constexpr double kModelMinGrade = 0.5, kModelMaxGrade = 2.5;

// A body given by its vertices (a file, an array) read through the model's
// faces: ConfigError, starting with `what` (the body: "body FILE"), when
// they are not in the body model's order (an edge of the mean body
// stretched more than ten times: vertices swapped, shuffled, another mesh)
// or the surface turns inwards (mirrored).
// `edges`: model_body_edges(model), made once for body after body (the
// Python module's predict); null makes them for this call.
struct ModelBodyEdges {
  std::vector<std::array<int, 2>> edges;  // the mean body's, of nonzero length
  std::vector<double> lengths;            // their lengths on the mean body
};
ModelBodyEdges model_body_edges(const Model& model);
void require_model_body_vertices(const Eigen::MatrixX3d& vertices, const Model& model, const std::string& what,
                                 const ModelBodyEdges* edges = nullptr);
// The same checks against a body model's mean body `mean` with the model's
// `model_faces`, for a command with no trained model (simulate --body, body
// --unpose); with the mesh's own `faces` (a file's: null for an array of
// points) also that nine in ten of its edges are the model's (ConfigError
// otherwise: its vertices re-indexed, an STL's triangle soup welded in
// another order).
ModelBodyEdges model_body_edges(const Eigen::MatrixX3d& mean, const Eigen::MatrixX3i& model_faces);
void require_body_model_mesh(const Eigen::MatrixX3d& vertices, const Eigen::MatrixX3i* faces, const Eigen::MatrixX3d& mean,
                             const Eigen::MatrixX3i& model_faces, const std::string& what);

// A batch of one. ConfigError for a mesh of the wrong vertex count (saying the
// expected one), in other units, given to a graph that takes body parameters,
// and for a model of several sizes without a garment size.
SampleBatch model_body_batch(const Model& model, const ModelBodyInput& input);

struct PreparedBodies {
  // Per body: what moves what the model predicts for it back where (and the
  // way) the body stood (BodyMove::back; the identity when it was not moved).
  std::vector<BodyMove> moved_by;
  // Per body: the pose read off a body mesh given posed to a model of posed
  // drapes (pose_fit.hpp; its body in the batch is then the mesh unposed),
  // empty for a body given at rest. BodyPreparation::pose drapes it so.
  std::vector<Pose> given_poses;
  // Per body: its mesh was read at rest (within kPosedAngleDegrees of the
  // rest pose at every joint): a pose given with it is the body's pose.
  std::vector<char> given_at_rest;
  std::vector<Notice> notices;
  // Body i was given as a mesh in a pose of its own (read off it, and not
  // the rest pose): no other pose applies to it.
  bool given_posed(std::size_t i) const {
    return i < given_poses.size() && !given_poses[i].empty() && !(i < given_at_rest.size() && given_at_rest[i]);
  }
};

// Makes batches ready for one model: built once per model (what does not
// depend on the body -- the training domain, the garment's loop on the mean
// body -- is read or measured here), then prepare() per batch. `domain`: the
// model file's (read_domain), none for a model that records none.
class BodyPreparation {
 public:
  BodyPreparation(const Model& model, std::optional<ModelDomain> domain);
  // With strict, a body outside the domain (or a model without one) is a
  // ConfigError starting "<strict_option>: " instead of a warning. Without
  // measure, only the placement: the domain check and the fit note measure
  // the body (its volume, its girths over the chest band, its distance to
  // every training body: about 5 ms for the parametric body), several times
  // the coarse model's forward pass.
  // given_meshes: the bodies were given as meshes (a file, an array), and are
  // placed by the body model's anchor (body_anchor.hpp, found on first use:
  // about 0.2 s); false for bodies the model's body plugin made, which stand
  // where it makes them. A model of posed drapes reads the pose off each
  // mesh given (pose_fit.hpp, about a second a body) unless pose_given (the
  // caller gives the bodies' pose, so a body is at rest unless its limbs
  // turn past kPosedLimbDegrees: refused then in pose(), two poses for one body).
  PreparedBodies prepare(SampleBatch& batch, bool strict, const std::string& strict_option = "--strict",
                         bool measure = true, bool given_meshes = true, bool pose_given = false) const;
  // pose_model_batch, then the pose against the domain's trained joint
  // angles: a warning per angle outside (with strict, a ConfigError starting
  // "<strict_option>: "), and a warning (strict: ConfigError) for a pose in
  // which the body passes through itself (describe_pose_crossings: an exact
  // triangle-triangle test of the posed body, about 15 ms). Run after prepare().
  // For a model that takes the garment's grade: each body of a batch that
  // has no grades in the size the tailor's rule gives it (what prepare()
  // chooses), measured where bodies stand in a scene wherever it is given;
  // the notes naming each size. Nothing for other models or given grades.
  std::vector<Notice> choose_sizes(SampleBatch& batch) const;
  // `prepared`: what prepare() said of this batch; a body given posed is
  // draped in the pose read off it (PreparedBodies::given_poses), and `pose`
  // must then be empty (ConfigError: two poses for one body).
  // check = false leaves out the self-crossing test (Python's check=False);
  // refuse_crossing makes a pose in which the body passes through itself a
  // ConfigError whatever `strict` (an optimisation: the contact cannot keep
  // cloth off a body with no inside, as drape body and simulate refuse it).
  std::vector<Notice> pose(SampleBatch& batch, const Pose& pose, bool strict,
                           const std::string& strict_option = "--strict", const PreparedBodies* prepared = nullptr,
                           bool check = true, bool refuse_crossing = false) const;
  const std::optional<ModelDomain>& domain() const { return domain_; }

 private:
  const Model& model_;
  std::optional<ModelDomain> domain_;
  double garment_loop_;  // m, the model garment's narrowest loop on the mean body (NaN: none, or a sized model)
  void choose_sizes(SampleBatch& batch, bool strict, const std::string& strict_option, std::vector<Notice>& notices) const;
  std::optional<SizeTable> size_chart_;  // a model taking garment_grade: its training data's size chart
  // pose_given: a pose is asked for this body, so a mesh read at rest is as
  // expected and not noted.
  BodyMove unpose_given(SampleBatch& batch, int i, Pose& pose, bool& at_rest, bool pose_given,
                        std::vector<Notice>& notices) const;
  // The largest turn of a bone of body i against the mean body's (LimbFit::turns), degrees.
  double most_turned(const SampleBatch& batch, int i) const;
  GivenBodyFrame given_;  // turns, places and checks bodies given as meshes (given_body.hpp)
};

// For a model taking garment_grade: the grade a caller asked for, a number
// (checked against kModelMinGrade..kModelMaxGrade) or a size of the model's
// size chart; none for "auto" or nothing (prepare() chooses per body).
// ConfigError for both, an unknown size or a grade out of range.
std::optional<double> requested_garment_grade(const Model& model, const std::optional<std::string>& size,
                                              const std::optional<double>& grade);

// The size chart a model taking garment_grade was trained with (its metadata
// size_chart), none when it records none.
std::optional<SizeTable> model_size_chart(const Model& model);


}  // namespace drape
