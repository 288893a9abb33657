#pragma once
// Which size of a graded garment a body needs, by a tailor's rule, for scenes
// whose garment says `size: auto` (docs/garments.md, "Which size fits which
// body").
//
// The rule works with girths, as a size chart does:
// - the body's girth is the largest tape measure (geometry::horizontal_girth)
//   of its torso between 58 % and 72 % of its height above its soles, the
//   part a T-shirt covers: the chest, or the belly where that is larger;
// - a size's girth is the narrowest loop of its fabric over the same band of
//   the mean body (the torso of a tee is straight; narrowest, so that no
//   loop through an armhole counts);
// - ease = garment girth / body girth - 1. The default size on the mean body
//   has the design ease (14 % for the regular T-shirt on the mean man);
// - the size chosen is the one whose ease is nearest the design ease among
//   those with ease >= 0 (a garment smaller than the body would be stretched
//   onto it); when no size has ease >= 0 the garment does not fit the body,
//   and simulating it would hand back a drape stretched over the body and
//   unsettled: the caller says so instead.
#include <drape/registry.hpp>
#include <drape/scene/auto_grade.hpp>
#include <drape/scene/scene.hpp>
#include <drape/scene/simulation.hpp>
#include <drape/scene/size_table.hpp>

#include <Eigen/Core>

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace drape {

class GivenBodyFrame;  // bodies/given_body.hpp

inline constexpr double kGirthBandLow = 0.58, kGirthBandHigh = 0.72;  // fractions of the height

// True when the scene's garment has a `size` parameter set to "auto".
bool garment_size_is_auto(const Scene& scene);
// The default of the scene's garment's size parameter (its design size).
std::string default_garment_size(const Registry& registry, const Scene& scene);
// The scene with its garment's size set.
Scene with_garment_size(const Scene& scene, const std::string& size);
// The body's girth by the rule above (vertices of a body mesh, Y up).
double body_girth(const Eigen::MatrixX3d& body, const Eigen::MatrixX3i& faces);
// A garment's girth by the rule above: the narrowest loop of its rest mesh
// (`garment`, dressed on `mean_body`) over the band; infinity when no loop of
// it goes around the body there.
double garment_girth(const Eigen::MatrixX3d& garment, const Eigen::MatrixX3i& garment_faces,
                     const Eigen::MatrixX3d& mean_body);
// The same loops measured in the garment's material space (its cloth at
// rest, Mesh::uv in metres): the narrowest over the band, NaN when the
// garment has no material space or no loop goes around the body. What the
// cloth spans unstretched, where garment_girth measures the 3D shape (a
// pattern cut small but modelled around the body, or a full one crumpled
// inside it, differ there).
double garment_material_girth(const Mesh& garment, const Eigen::MatrixX3d& mean_body);
// Whether a garment dressed on `mean_body` lies beside its torso instead of
// around it: no loop of it over the band encloses the body's vertical axis
// while one of its loops there is at least half as long as the body's girth
// at that height (a torso's tube of cloth beside the body: a top placed 25
// cm in front of it, both panels clear of the chest, passes dressing and the
// start checks, and its drape hangs as an apron). Empty when it goes around,
// or has no torso-sized loop there (trousers, a sleeve); else what was
// measured, for a refusal: the loop, the body's girth and where the cloth's
// centre lies from the body's axis.
std::string garment_beside_body(const Eigen::MatrixX3d& garment, const Eigen::MatrixX3i& garment_faces,
                                const Eigen::MatrixX3d& mean_body, const Eigen::MatrixX3i& body_faces);
// The garment's ease on `body`: garment_girth / body_girth - 1 (negative: the
// garment is smaller than the body). NaN when either cannot be measured.
double garment_ease(const Eigen::MatrixX3d& garment, const Eigen::MatrixX3i& garment_faces,
                    const Eigen::MatrixX3d& mean_body, const Eigen::MatrixX3d& body, const Eigen::MatrixX3i& body_faces);
// The same with the garment's loop measured already (garment_girth): what a
// caller checking many bodies against one garment measures once.
double garment_ease(double garment_loop, const Eigen::MatrixX3d& body, const Eigen::MatrixX3i& body_faces);
// The sizes of a scene's garment, each built as a Simulation once, with their
// girths and the design ease; then a choice per body. ConfigError when the
// scene's garment has no size parameter with choices. choose() and
// simulation() are const and may be called from threads.
class SizeChart {
 public:
  SizeChart(const Registry& registry, const Scene& scene);
  ~SizeChart();
  // The size for `body` (the scene body model's topology).
  SizeChoice choose(const Eigen::MatrixX3d& body) const;
  const std::vector<std::string>& sizes() const { return sizes_; }
  // The sizes' girths, design size and ease: what a dataset and a model keep.
  const SizeTable& table() const { return table_; }
  // The scene with that size (one of sizes()), ready to run; the default
  // size's gives the scene's body model and bodies.
  const Simulation& simulation(const std::string& size) const;
  const Simulation& design() const { return simulation(design_size_); }

 private:
  std::vector<std::string> sizes_;
  std::string design_size_;
  std::vector<std::unique_ptr<Simulation>> simulations_;  // one per size, in the order of sizes_
  SizeTable table_;
};

// What a command runs a scene with: its one Simulation, with size: auto the
// SizeChart of every size (garment_size_is_auto), or with grade: auto the
// garment graded per body (auto_grade.hpp).
class SceneSimulations {
 public:
  SceneSimulations(const Registry& registry, const Scene& scene);
  ~SceneSimulations();
  // The scene's simulation; with size: auto the design size's, with grade:
  // auto the ungraded garment's (the body model, the bodies and the dataset
  // template come from it).
  const Simulation& design() const;
  bool auto_size() const { return chart_ != nullptr; }
  bool auto_grade() const { return grades_ != nullptr; }
  const SizeChart* chart() const { return chart_.get(); }      // with size: auto
  const AutoGrade* grades() const { return grades_.get(); }    // with grade: auto
  // The simulation `body` is draped with: design() without size: auto or
  // grade: auto, else the size the chart chooses (into *choice when given) or
  // the grade the body needs (into *grade_choice). ConfigError "<what>:
  // garment ... does not fit this body: <summary>" when none fits.
  const Simulation& for_body(const Eigen::MatrixX3d& body, const std::string& what, SizeChoice* choice = nullptr,
                             GradeChoice* grade_choice = nullptr) const;
  // What turns, places and checks a body given as a mesh
  // (services/scene_body.hpp) for the scene's body model: found once, on
  // first use (given_body.hpp).
  const GivenBodyFrame& given_bodies() const { return *given_; }

 private:
  std::unique_ptr<GivenBodyFrame> given_;
  std::string garment_;
  std::unique_ptr<SizeChart> chart_;
  std::unique_ptr<AutoGrade> grades_;
  std::unique_ptr<Simulation> own_;
};

}  // namespace drape
