// grade: auto (scene/auto_grade.hpp).
#include <drape/scene/auto_grade.hpp>

#include <drape/bodies/fit_body.hpp>
#include <drape/errors.hpp>
#include <drape/garment_grading.hpp>
#include <drape/scene/garment_size.hpp>
#include <drape/vertex_count.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace drape {
namespace {

long grade_key(double grade) { return std::lround(grade / kAutoGradeStep); }

std::string step_name(long key) {
  char name[16];
  std::snprintf(name, sizeof name, "g%.2f", kAutoGradeStep * static_cast<double>(key));
  return name;
}

}  // namespace

std::string GradeChoice::summary() const {
  char text[200];
  std::snprintf(text, sizeof text, "the body's chest or belly %.3f m; grade %.3f gives the design ease, %.2f worn",
                body_girth, exact, grade);
  std::string line = text;
  if (at_smallest) {
    std::snprintf(text, sizeof text, " (the smallest grade the body model dresses: the thinnest body it makes at its "
                  "mean height, where a grade is dressed, has %.2f of the mean body's girth)", thinnest);
    line += text;
  }
  return line;
}

AutoGrade::AutoGrade(const Registry& registry, const Scene& scene) : registry_(registry), scene_(scene) {
  scene_.garment_grade_auto = false;
  scene_.garment_grade = 1.0;
  if (garment_size_is_auto(scene_))
    throw ConfigError({scene.file, 0}, "garment `size: auto` and `grade: auto` choose the same thing twice: keep one "
                                       "(size: auto among the garment's sizes, grade: auto any grade within 0.5-2)");
  design_ = std::make_unique<Simulation>(registry_, scene_);
  const Mesh& garment = design_->garment().mesh;
  const Eigen::MatrixX3i& body_faces = design_->body_model().faces();
  design_loop_ = garment_girth(garment.vertices, garment.faces, design_->mean_body());
  design_ease_ = garment_ease(design_loop_, design_->mean_body(), body_faces);
  if (!std::isfinite(design_loop_) || !std::isfinite(design_ease_))
    throw ConfigError({scene.file, 0}, "garment `grade: auto` grades by the tailor's rule, which measures a garment "
                                       "that goes around the torso between 58 and 72 % of the body's height; garment '" +
                                           scene.garment + "' does not (trousers, a skirt): give it a grade");
  table_.design = step_name(grade_key(1.0));
  table_.design_ease = design_ease_;
  // A grade is dressed on the body of its girth (fit_body.hpp) and every
  // morph starts there. Below the thinnest body the model reaches (the
  // parametric body at its mean height: 0.56 of the mean girth at BMI 10) a
  // graded garment would start tighter than that body, and every drape in
  // it was refused at the start as a crossing. So the chart starts at the
  // first step the model dresses; a body thinner still wears that step, a
  // little looser than designed (GradeChoice::at_smallest says so).
  const double fit_grade = design_->garment().fit_grade;
  thinnest_ = fit_body(design_->body_model(), kMinGrade * fit_grade).girth_ratio / fit_grade;
  // fit_body meets a girth to 0.2 %: a step that close above the thinnest is dressed on it.
  const long smallest_key = std::max(grade_key(kMinGrade), static_cast<long>(std::ceil(thinnest_ * (1 - 2e-3) / kAutoGradeStep)));
  every_grade_ = table_;
  for (long key = grade_key(kMinGrade); key <= grade_key(kMaxGrade); ++key) {
    const auto step = std::make_pair(step_name(key), design_loop_ * kAutoGradeStep * static_cast<double>(key));
    every_grade_.girth.push_back(step);
    if (key >= smallest_key) table_.girth.push_back(step);
  }
}

AutoGrade::~AutoGrade() = default;

GradeChoice AutoGrade::choose(const Eigen::MatrixX3d& body, const std::string& what) const {
  const Simulation& d = design();
  require_vertex_count(body.rows(), d.mean_body().rows(), "the body",
                       "the scene's body model '" + d.scene().body_model + "'");
  GradeChoice choice;
  choice.body_girth = body_girth(body, d.body_model().faces());
  // The garment's loop grows with the grade; the ease is loop / girth - 1.
  choice.exact = (1.0 + design_ease_) * choice.body_girth / design_loop_;
  const SizeChoice step = table_.choose(choice.body_girth);
  // Too large for grade 2, or so small that even grade 0.5 hangs off it.
  if (step.size.empty() || choice.exact < kMinGrade - kAutoGradeStep / 2) {
    char text[400];
    std::snprintf(text, sizeof text,
                  "%s: garment '%s' with grade: auto cannot fit this body: its chest or belly is %.3f m, the garment's "
                  "narrowest loop %.3f m on the mean body with %+.1f %% ease there, so this body needs grade %.2f, "
                  "outside the 0.5-2 a grade may take",
                  what.c_str(), scene_.garment.c_str(), choice.body_girth, design_loop_, 100.0 * design_ease_, choice.exact);
    throw ConfigError(text);
  }
  const long key = grade_key(table_.grade(step.size));
  choice.grade = kAutoGradeStep * static_cast<double>(key);
  // Worn looser than the rule would have it only because no smaller grade
  // can be dressed: the rule over every grade chooses a smaller one. (A
  // garment made tight rounds up anyway: MakeHuman's T-shirt at grade 0.861
  // wears 0.90 either way.)
  const SizeChoice unbounded = every_grade_.choose(choice.body_girth);
  choice.at_smallest = !unbounded.size.empty() && grade_key(every_grade_.grade(unbounded.size)) < key;
  choice.thinnest = thinnest_;
  return choice;
}

const Simulation& AutoGrade::simulation(double grade) const {
  const long key = grade_key(grade);
  if (key == grade_key(1.0)) return *design_;
  std::lock_guard<std::mutex> guard(mutex_);  // built under the lock: threads wanting one grade build it once
  auto it = graded_.find(key);
  if (it == graded_.end()) {
    Scene graded = scene_;
    graded.garment_grade = kAutoGradeStep * static_cast<double>(key);
    it = graded_.emplace(key, std::make_unique<Simulation>(registry_, graded)).first;
  }
  return *it->second;
}

}  // namespace drape
