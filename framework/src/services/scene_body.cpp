// scene_body and drape_scene_body (services/scene_body.hpp).
#include <drape/bodies/body.hpp>
#include <drape/bodies/posed_body.hpp>
#include <drape/garment_grading.hpp>
#include <drape/geometry/body_units.hpp>
#include <drape/geometry/girth.hpp>
#include <drape/io/mesh_io.hpp>
#include <drape/training/model_domain.hpp>
#include <drape/services/model_body.hpp>
#include <drape/services/scene_body.hpp>
#include <drape/bodies/given_body.hpp>
#include <drape/scene/garment_size.hpp>
#include <drape/errors.hpp>
#include <drape/registry.hpp>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace drape {
namespace {

// Which of the request's values lies outside what the body model declares
// it reaches (its BMI range, a shape parameter of that name's range, a
// proportion's range): "bmi", "height", "sex", "girth", or none.
std::string unreachable_value(const BodyModel& model, const BodyRequest& request) {
  const auto [bmi_lo, bmi_hi] = model.bmi_range();
  if (!(request.bmi >= bmi_lo && request.bmi <= bmi_hi)) return "bmi";
  const std::vector<std::string> names = model.shape_names();
  const std::vector<std::pair<double, double>> ranges = model.shape_ranges();
  for (const auto& [key, value] : {std::pair<const char*, double>{"height", request.height}, {"sex", request.sex}})
    for (std::size_t i = 0; i < names.size() && i < ranges.size(); ++i)
      if (names[i] == key && !(value >= ranges[i].first && value <= ranges[i].second)) return key;
  for (const BodyModel::Proportion& p : model.proportions())
    if (const auto it = request.proportions.find(p.name);
        it != request.proportions.end() && !(it->second >= p.min && it->second <= p.max))
      return "girth";
  return "";
}

// The request's shape, a value the body model cannot reach named where it
// was written (the scene's file and line, or the command line): the body
// model's own refusal ("height 0.5 m is outside the reachable range") named
// no file, line nor key, which an outside check found for height, BMI and
// --girth, where every other bad value of a scene names all three.
Eigen::VectorXd solve_where_written(const Simulation& design, const BodyRequest& request) {
  try {
    return design.shape_for(request);
  } catch (const ConfigError& e) {
    const std::string key = unreachable_value(design.body_model(), request);
    if (key.empty()) throw;
    if (key == "girth") throw ConfigError(SourceLocation{"command line", 0}, std::string("--girth: ") + e.what());
    const auto& shape = design.scene().shape;
    const auto it = shape.find(key);
    throw ConfigError(it != shape.end() ? it->second.where : SourceLocation{design.scene().file, 0},
                      "body shape: " + key + ": " + e.what());
  }
}

// How a garment of one size fits this body, told before anything is
// simulated: its ease (garment_size.hpp's tailor's rule, on any garment that
// goes around the torso) against the ease it has on the mean body it was
// made for, and the grade that would give it that ease here. Nothing is said
// of a garment within 5 points of its design ease, or one that does not go
// around the torso band (trousers, a skirt).
// The ungraded garment's narrowest loop on the mean body (its design): as
// dressed for a garment of grade 1 (what the notes always measured), else as
// its template built it (Simulation::design_loop: dressing pushes a graded
// garment smaller than the body out onto it, and grading a dressed one back
// would not undo that).
double design_loop(const Simulation& design) {
  const Mesh& garment = design.garment().mesh;
  if (design.scene().garment_grade == 1.0) return garment_girth(garment.vertices, garment.faces, design.mean_body());
  return design.design_loop();
}

// The grade of the template whose loop gives a body of girth `around` the design ease.
std::string grade_text(double design_loop, double design_ease, double around) {
  const double grade = (1.0 + design_ease) * around / design_loop;
  if (!(grade >= kMinGrade && grade <= kMaxGrade)) return "no grade within 0.5-2 gives it its design ease";
  char text[80];
  std::snprintf(text, sizeof text, "garment: {grade: %.2f} gives it its design ease", grade);
  return text;
}

// How far down a top reaches on this body against the mean body it was made
// for (the tailor's rule's other measure): its length from its neckline as
// a share of the torso from there to the crotch. The neckline rides at the
// same share of the body's height, the garment's length does not change, so
// on a taller body a shirt ends higher. Noted when the share moves by more
// than 10 points, with the grade whose length gives the design share (the
// length scales with the grade). Nothing for a garment that reaches below
// the crotch on the mean body (trousers, a dress) or a body without one.
void note_length(const Simulation& design, SceneBody& out) {
  const Mesh& garment = design.garment().mesh;
  const Eigen::MatrixX3i& faces = design.body_model().faces();
  const Eigen::MatrixX3d& mean = design.mean_body();
  const double soles0 = mean.col(1).minCoeff(), height0 = mean.col(1).maxCoeff() - soles0;
  const double top = garment.vertices.col(1).maxCoeff() - soles0, hem = garment.vertices.col(1).minCoeff() - soles0;
  const double crotch0 = geometry::crotch_height(mean, faces), crotch = geometry::crotch_height(out.vertices, faces);
  if (!std::isfinite(crotch0) || !std::isfinite(crotch) || hem <= crotch0 || top <= crotch0) return;
  const double height = out.vertices.col(1).maxCoeff() - out.vertices.col(1).minCoeff();
  const double length = top - hem, top_here = top * height / height0;
  const double share0 = length / (top - crotch0), share = length / (top_here - crotch);
  if (!(top_here > crotch) || std::abs(share - share0) <= 0.10) return;
  char text[400];
  std::snprintf(text, sizeof text,
                "the garment reaches %.0f %% of the way from its neckline to this body's crotch, against %.0f %% on the mean "
                "body it was made for (%.2f m tall; this one %.2f m): it ends %s, as %s; garment: {grade: %.2f} gives it "
                "its design length",
                100.0 * share, 100.0 * share0, height0, height, share < share0 ? "higher" : "lower",
                share < share0 ? "a shorter shirt would" : "a longer shirt would", design.scene().garment_grade * share0 / share);
  out.notes.push_back(text);
}

void note_fit(const Simulation& design, SceneBody& out) {
  const Mesh& garment = design.garment().mesh;
  const Eigen::MatrixX3i& body_faces = design.body_model().faces();
  // A garment modelled much larger than its cloth (said by choose_size): its
  // fit told by the cloth (its shape would call it far looser than it settles).
  const bool by_cloth = !design.shape_note().empty();
  // A graded garment as graded, before dressing pushed it about (design_loop).
  const double loop = by_cloth                                  ? design.cloth_loop()
                      : design.scene().garment_grade == 1.0 ? garment_girth(garment.vertices, garment.faces, design.mean_body())
                                                             : design.placed_loop();
  const double ease = garment_ease(loop, out.vertices, body_faces);
  const double loop0 = by_cloth ? design.cloth_loop() / design.scene().garment_grade : design_loop(design);
  const double design_ease = garment_ease(loop0, design.mean_body(), body_faces);
  if (!std::isfinite(ease) || !std::isfinite(design_ease) || std::abs(ease - design_ease) <= 0.05) return;
  char text[400];
  std::snprintf(text, sizeof text,
                "the garment is %.1f %% %s around than this body's chest or belly (it has %+.1f %% ease here, %+.1f %% on "
                "the mean body it was made for; the tailor's rule of docs/garments.md)%s; %s",
                100.0 * std::abs(ease), ease < 0 ? "smaller" : "larger", 100.0 * ease, 100.0 * design_ease,
                ease < 0 ? ", so it is stretched onto the body or rides up over it" : "",
                grade_text(loop0, design_ease, loop / (1.0 + ease)).c_str());
  std::string note = text;
  if (design.scene().garment_params.count("size")) note += " (or size: auto, which picks one of its sizes)";
  out.notes.push_back(note);
}

// The size a body wears with size: auto (the design size's simulation otherwise).
void choose_size(const SceneSimulations& simulations, const std::string& name, SceneBody& out) {
  // A garment modelled much larger around than its cloth, whatever its size or grade (cloth_fit.hpp).
  if (const std::string& note = simulations.design().shape_note(); !note.empty()) out.notes.push_back(note);
  if (simulations.auto_grade()) {  // graded to this body's girth; lengths grow by the grading rule
    GradeChoice choice;
    out.simulation = &simulations.for_body(out.vertices, name, nullptr, &choice);
    out.grade = choice;
    return;
  }
  if (!simulations.auto_size()) {
    out.simulation = &simulations.design();
    // A garment whose cloth cannot be put on its start body is refused when
    // it runs, saying what to change (its pattern's scale, its grade): a fit
    // note first advised a grade that is refused the same way (an outside check).
    if (!simulations.design().start_refusal().empty()) return;
    note_fit(simulations.design(), out);
    note_length(simulations.design(), out);
    return;
  }
  SizeChoice choice;
  out.simulation = &simulations.for_body(out.vertices, name, &choice);
  out.size = std::move(choice);
}

// Poses the chosen body (its size already chosen on the unposed one).
void pose_chosen(const SceneSimulations& simulations, const Pose* pose, SceneBody& out) {
  const Simulation& design = simulations.design();
  const Pose& wanted = pose ? *pose : design.target_pose();
  if (wanted.empty()) return;
  out.pose = wanted;
  out.unposed = out.vertices;
  out.vertices = pose_vertices(design.body_model(), design.scene().body_model, out.unposed, wanted);
}

}  // namespace

SceneBody scene_body(const SceneSimulations& simulations, const Eigen::MatrixX3d& given, const std::string& name,
                     const Pose* pose, const Eigen::MatrixX3i* faces) {
  const Simulation& design = simulations.design();
  Mesh mesh;
  mesh.vertices = given;
  require_vertex_count(mesh, static_cast<int>(design.mean_body().rows()), name,
                       "the scene's body model '" + design.scene().body_model + "' has that many");
  check_body_units(given, "body " + name);
  require_body_model_mesh(given, faces, design.mean_body(), design.body_model().faces(), "body " + name);
  SceneBody out;
  out.vertices = given;
  const GivenBodyFrame& given_bodies = simulations.given_bodies();
  const bool posed = !given_bodies.limbs().posed(design.mean_body(), out.vertices).empty();
  const Eigen::Vector3d reference = body_placement(design.mean_body());
  if (posed && design.body_model().poseable()) {
    // Unposed, so that the body morphs at rest and then takes the pose along
    // its path (Simulation::run), as a body given at rest with its pose does.
    if (pose && !pose->empty())
      throw ConfigError("body " + name + " is given posed and a pose is given too: give the posed mesh alone (its pose "
                        "is read off it), or the body at rest with the pose");
    const GivenPosedBody unposed =
        unpose_given_body(out.vertices, design.body_model(), design.mean_body(), &given_bodies.anchor(), reference,
                          Eigen::Vector3d::Constant(kBodyModelPlacementSpread), "body " + name);
    if (!unposed.outside.empty()) throw ConfigError(unposed.outside);  // (its lean and pose are misread too)
    if (!unposed.leaning.empty()) throw ConfigError(unposed.leaning);  // gravity would act across the drape
    out.moved_by = unposed.moved;
    if (!unposed.turned.empty()) out.notes.push_back("the body " + unposed.turned);
    out.notes.push_back(unposed.pose_note);
    if (!unposed.warning.empty()) out.notes.push_back(unposed.warning);
    if (!design.target_pose().empty())
      out.notes.push_back("the scene's own pose (" + format_pose(design.target_pose()) +
                          ") gives way to the pose read off the body mesh");
    choose_size(simulations, name, out);
    pose_chosen(simulations, &unposed.fit.pose, out);
    return out;
  }
  if (posed)  // a body model without a skeleton: nothing to unpose it with
    out.notes.push_back("the body looks posed (a limb turned more than " + std::to_string(static_cast<int>(kPosedLimbDegrees)) +
                        " degrees against the mean body at rest): it is morphed to as given, not along the path a pose "
                        "takes");
  std::string turned;
  // Placed by the body model's anchor: exactly where the model makes the body, not only near.
  out.moved_by = place_given_body(out.vertices, design.mean_body(), &given_bodies.anchor(), reference,
                                  Eigen::Vector3d::Constant(kBodyModelPlacementSpread), posed, "body " + name, &turned);
  if (!turned.empty()) out.notes.push_back("the body " + turned);
  if (!out.moved_by.offset.isZero(0.0)) {
    char where[120];
    std::snprintf(where, sizeof where, "the body model's bodies stand (soles at y = %.3f, the midline at x = 0)",
                  reference[1]);
    out.notes.push_back("the body " + placement_note(out.moved_by.offset.transpose(), where));
  }
  choose_size(simulations, name, out);
  pose_chosen(simulations, pose, out);
  return out;
}

SceneBody scene_body(const SceneSimulations& simulations, const BodyRequest& request, const std::string& name,
                     const Pose* pose) {
  const Simulation& design = simulations.design();
  SceneBody out;
  out.vertices = design.body_vertices(solve_where_written(design, request));
  choose_size(simulations, name, out);
  pose_chosen(simulations, pose, out);
  return out;
}

namespace {

// "its parameter gender: 0 (default 1) fits it to another body than ..." for
// each garment parameter that fits the garment to the body a drape starts
// from (ParamSpec::fits_start_body: a MakeHuman outfit's body sliders) and
// that the scene sets off its default; "" when none. An outside check's
// gender: 0 was told to model the outfit around the mean body.
std::string body_sliders_moved(const Scene& scene) {
  const PluginDescriptor* garment = Registry::load_default().find(scene.garment);
  if (!garment) return "";
  std::string out;
  for (const ParamSpec& spec : garment->params) {
    const auto set = scene.garment_params.find(spec.name);
    if (!spec.fits_start_body || set == scene.garment_params.end()) continue;
    const std::string value = set->second.node.IsScalar() ? set->second.node.Scalar() : std::string("?");
    bool same = value == spec.default_value;
    try {
      same = same || std::stod(value) == std::stod(spec.default_value);
    } catch (const std::exception&) {
    }
    if (same) continue;
    out += (out.empty() ? "" : ", ") + spec.name + ": " + value + " (default " + spec.default_value + ")";
  }
  if (out.empty()) return "";
  return "its parameter" + std::string(out.find(", ") == std::string::npos ? " " : "s ") + out +
         " fit it to another body than the one a drape starts from (the body model's mean shape): keep the default";
}

}  // namespace

std::string start_fit_hint(const Simulation& design) {
  // A pattern cut too small was refused by its cloth's own measure (run()):
  // nothing to add from the 3D shape, which it may share with one that fits.
  if (!design.start_refusal().empty()) return "";
  const Eigen::MatrixX3i& body_faces = design.body_model().faces();
  const double loop = design.placed_loop();  // before dressing pushed it out onto the body
  // Put on the body it is cut for: the mean body, or its size's fit body (fit_body.hpp).
  const double ease = garment_ease(loop, design.fit_body(), body_faces);
  if (!(ease < 0)) return "";  // fits the body it is dressed on, or does not go around the torso
  const double loop0 = design_loop(design);
  const double design_ease = garment_ease(loop0, design.mean_body(), body_faces);
  const double around = loop / (1.0 + ease);
  char text[600];
  // Its cloth long enough (the start refusal passed it: cloth_fit.hpp) and
  // no other grade to name (an ungraded garment's design is itself): the
  // shape is what lies inside the body. A grade hint would name its own grade.
  const double grade = (1.0 + design_ease) * around / loop0;
  // A template fitted to another body by its parameters: that is the cause, and keeping their defaults the remedy.
  if (const std::string sliders = body_sliders_moved(design.scene()); !sliders.empty()) {
    std::snprintf(text, sizeof text,
                  "the garment as modelled is %.1f %% smaller around than the body it is put on before the body morphs "
                  "(its narrowest loop over the chest band %.3f m, the body's chest or belly %.3f m): ",
                  -100.0 * ease, loop, around);
    return text + sliders;
  }
  if (std::isfinite(design.cloth_loop()) && std::isfinite(grade) &&
      std::abs(grade - design.scene().garment_grade) < 0.03) {
    std::snprintf(text, sizeof text,
                  "the garment as modelled is %.1f %% smaller around than the body it is put on before the body morphs "
                  "(its narrowest loop over the chest band %.3f m, the body's chest or belly %.3f m), though its cloth "
                  "at rest is %.3f m around: it is modelled inside the body; model it around the body model's mean body "
                  "(drape body writes it), not inside it",
                  -100.0 * ease, loop, around, design.cloth_loop());
    return text;
  }
  std::snprintf(text, sizeof text,
                "the garment is %.1f %% smaller around than the body it is put on before the body morphs (its "
                "narrowest loop over the chest band %.3f m, the body's chest or belly %.3f m), so it cannot be put on; ",
                -100.0 * ease, loop, around);
  return text + (std::isfinite(design_ease) ? grade_text(loop0, design_ease, around) : std::string("grade it up"));
}

SimulationResult drape_scene_body(const SceneBody& body, SimulationOptions options) {
  // The caller's start states are in the given body's frame; the simulation
  // runs in the placed one.
  Eigen::MatrixX3d start_garment, start_body;
  if (options.start_garment) {
    start_garment = body.moved_by.placed(*options.start_garment);
    options.start_garment = &start_garment;
  }
  if (options.start_body) {
    start_body = body.moved_by.placed(*options.start_body);
    options.start_body = &start_body;
  }
  if (!body.pose.empty()) {
    options.target_pose = &body.pose;
    options.unposed_target = &body.unposed;
  }
  SimulationResult r = [&] {
    try {
      return body.simulation->run(body.vertices, options);
    } catch (const ConfigError& e) {  // a start the contact refuses: say when the garment is too small to put on
      const std::string hint = start_fit_hint(*body.simulation);
      if (hint.empty()) throw;
      throw ConfigError(std::string(e.what()) + "; " + hint);
    }
  }();
  if (!body.moved_by.is_identity()) {
    r.garment = body.moved_by.back(r.garment);
    r.body = body.moved_by.back(r.body);
  }
  return r;
}

}  // namespace drape
