// scene_body and drape_scene_body (services/scene_body.hpp).
#include <drape/bodies/body.hpp>
#include <drape/geometry/body_units.hpp>
#include <drape/io/mesh_io.hpp>
#include <drape/training/model_domain.hpp>
#include <drape/services/scene_body.hpp>

#include <cstdio>

namespace drape {
namespace {

// The size a body wears with size: auto (the design size's simulation otherwise).
void choose_size(const SceneSimulations& simulations, const std::string& name, SceneBody& out) {
  if (!simulations.auto_size()) {
    out.simulation = &simulations.design();
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
