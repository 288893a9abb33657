// scene_body and drape_scene_body (services/scene_body.hpp).
#include <drape/bodies/body.hpp>
#include <drape/garment_grading.hpp>
#include <drape/geometry/body_units.hpp>
#include <drape/io/mesh_io.hpp>
#include <drape/training/model_domain.hpp>
#include <drape/services/scene_body.hpp>

#include <cmath>
#include <cstdio>

namespace drape {
namespace {

// How a garment of one size fits this body, told before anything is
// simulated: its ease (garment_size.hpp's tailor's rule, on any garment that
// goes around the torso) against the ease it has on the mean body it was
// made for, and the grade that would give it that ease here. Nothing is said
// of a garment within 5 points of its design ease, or one that does not go
// around the torso band (trousers, a skirt).
void note_fit(const Simulation& design, SceneBody& out) {
  const Mesh& garment = design.garment().mesh;
  const Eigen::MatrixX3i& body_faces = design.body_model().faces();
  const double loop = garment_girth(garment.vertices, garment.faces, design.mean_body());
  const double ease = garment_ease(loop, out.vertices, body_faces);
  // The ease the garment was made with: its ungraded loop on the mean body.
  const double scene_grade = design.scene().garment_grade;
  const double design_ease = garment_ease(loop / scene_grade, design.mean_body(), body_faces);
  if (!std::isfinite(ease) || !std::isfinite(design_ease) || std::abs(ease - design_ease) <= 0.05) return;
  // The grade of the template that gives this body that ease: loop * grade /
  // scene_grade = (1 + design_ease) * body girth.
  const double grade = scene_grade * (1.0 + design_ease) / (1.0 + ease);
  char text[400];
  std::snprintf(text, sizeof text,
                "the garment is %.1f %% %s around than this body's chest or belly (it has %+.1f %% ease here, %+.1f %% on "
                "the mean body it was made for; the tailor's rule of docs/garments.md)%s; %s",
                100.0 * std::abs(ease), ease < 0 ? "smaller" : "larger", 100.0 * ease, 100.0 * design_ease,
                ease < 0 ? ", so it is stretched onto the body or rides up over it" : "",
                grade < kMinGrade || grade > kMaxGrade ? "no grade within 0.5-2 gives it its design ease"
                                                       : ("garment: {grade: " + std::to_string(grade).substr(0, 4) +
                                                          "} gives it its design ease")
                                                             .c_str());
  std::string note = text;
  if (design.scene().garment_params.count("size")) note += " (or size: auto, which picks one of its sizes)";
  out.notes.push_back(note);
}

// The size a body wears with size: auto (the design size's simulation otherwise).
void choose_size(const SceneSimulations& simulations, const std::string& name, SceneBody& out) {
  if (!simulations.auto_size()) {
    out.simulation = &simulations.design();
    note_fit(simulations.design(), out);
    return;
  }
  SizeChoice choice;
  out.simulation = &simulations.for_body(out.vertices, name, &choice);
  out.size = std::move(choice);
}

}  // namespace

SceneBody scene_body(const SceneSimulations& simulations, const Eigen::MatrixX3d& given, const std::string& name) {
  const Simulation& design = simulations.design();
  Mesh mesh;
  mesh.vertices = given;
  require_vertex_count(mesh, static_cast<int>(design.mean_body().rows()), name,
                       "the scene's body model '" + design.scene().body_model + "' has that many");
  check_body_units(given, "body " + name);
  SceneBody out;
  out.vertices = given;
  const Eigen::Vector3d reference = body_placement(design.mean_body());
  if (const auto offset = move_to_placement(reference, Eigen::Vector3d::Constant(kBodyModelPlacementSpread), out.vertices)) {
    out.moved_by = offset->transpose();
    char where[120];
    std::snprintf(where, sizeof where, "the body model's bodies stand (soles at y = %.3f, centred in x and z)", reference[1]);
    out.notes.push_back("the body " + placement_note(*offset, where));
  }
  choose_size(simulations, name, out);
  return out;
}

SceneBody scene_body(const SceneSimulations& simulations, const BodyRequest& request, const std::string& name) {
  const Simulation& design = simulations.design();
  SceneBody out;
  out.vertices = design.body_vertices(design.shape_for(request));
  choose_size(simulations, name, out);
  return out;
}

SimulationResult drape_scene_body(const SceneBody& body, SimulationOptions options) {
  // The caller's start states are in the given body's frame; the simulation
  // runs in the placed one.
  Eigen::MatrixX3d start_garment, start_body;
  if (options.start_garment) {
    start_garment = options.start_garment->rowwise() - body.moved_by;
    options.start_garment = &start_garment;
  }
  if (options.start_body) {
    start_body = options.start_body->rowwise() - body.moved_by;
    options.start_body = &start_body;
  }
  SimulationResult r = body.simulation->run(body.vertices, options);
  if (!body.moved_by.isZero(0.0)) {
    r.garment.rowwise() += body.moved_by;
    r.body.rowwise() += body.moved_by;
  }
  return r;
}

}  // namespace drape
