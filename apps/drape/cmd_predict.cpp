// `drape predict [--model model.h5] (--body body.obj | --bmi 35) --out garment.obj`:
// the garment a trained model predicts for one body.
#include "command.hpp"
#include "model_body.hpp"

#include <drape/geometry/self_intersection.hpp>
#include <drape/geometry/penetration.hpp>
#include <drape/geometry/garment_clearance.hpp>
#include <drape/geometry/surface_crossings.hpp>
#include <drape/io/mesh_io.hpp>
#include <drape/training/model.hpp>
#include <drape/io/svg_figure.hpp>

#include <chrono>
#include <cstdio>
#include <iostream>

namespace drape::cli {
namespace DRAPE_UNITY_ID {  // the anonymous namespace, or a unique one in a unity build (command.hpp)

int run(const std::vector<std::string>& args) {
  po::options_description opts("drape predict");
  opts.add_options()("model", po::value<std::string>(),
                     (std::string("model file from drape train (default: the shipped pretrained model, models/") +
                      kDefaultModelFile +
                      ", on the human rig; models/tshirt-coarse.h5 is the mannequin's; with a pose, models/" +
                      posed_model_name + ", the human rig's too; models/tshirt-coarse-posed.h5 is the mannequin's)")
                         .c_str())(
      "out", po::value<std::string>(), "garment mesh to write (.obj, .ply, .gltf, .glb): the template's faces, the UVs of the size worn")(
      "body-out", po::value<std::string>(), "also write the body mesh")(
      "svg", po::value<std::string>(), "also draw the drape, the garment coloured by its distance to the body (.svg: front view; .html: a 3D viewer)");
  add_model_body_options(opts, "body mesh (.obj, .ply, .gltf, .glb, ...) in the model's body topology");
  add_push_out_option(opts, "then push the vertices inside the body out to this clearance in m");
  opts.add_options()("set", po::value<std::vector<std::string>>(),
                     "node.param=value: change a parameter of the model's graph that leaves the weights alone, e.g. "
                     "post.enabled=false (the network's drape without the shipped models' push-out; repeatable)");
  po::variables_map vm;
  const std::string usage =
      "drape predict [--model model.h5] (--body body.obj | --bmi 35 [--height 1.75 --sex 1 --girth belly=0.1]) --out garment.obj "
      "[--body-out body.obj]";
  if (!parse(usage, args, opts, {}, vm)) return 0;
  check_mesh_outputs(vm, {"out", "body-out"});
  const std::string model_file = model_file_for_body(vm, Registry::load_default(plugin_path(vm)), model_file_or_default(vm));
  if (!vm.count("model"))
    std::printf("model: %s (the shipped pretrained model%s; --model chooses another)\n", model_file.c_str(),
                std::filesystem::path(model_file).filename().string().find("posed") != std::string::npos ? " of posed drapes" : "");
  if (!vm.count("out")) throw UsageError("--out FILE is required (the garment mesh to write)");
  if (vm.count("body") == vm.count("bmi"))
    throw UsageError("give the body either as a mesh (--body FILE) or by its BMI (--bmi X), exactly one");

  const double pushed_to = push_out_margin(vm);
  Registry& registry = Registry::load_default(plugin_path(vm));
  Model model = Model::load(registry, model_file, parse_param_overrides(vm));
  if (model.assets_changed())
    std::cerr << "warning: the template assets differ from the ones " << model_file
              << " was trained with (a plugin changed since?)\n";
  BodyMove moved_by;  // predicted where (and as) the training bodies stood; written back where the body was
  std::vector<std::string> notes;  // what model_body printed, shown on the picture too
  const SampleBatch batch = model_body(model, vm, &moved_by, &notes);
  Mesh body;
  body.faces = model.assets().body.faces;
  body.vertices = moved_by.back(batch.body.mat(0).cast<double>());

  const auto start = std::chrono::steady_clock::now();
  const Tensor garment = model.predict(batch);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  Mesh out = model.assets().garment->mesh;  // the template's faces
  // The UVs of the pattern the body wears (its size's, for a model of drapes
  // in each body's own size), as simulate writes them: the file's own
  // material space, which render's strain and a user's tools read.
  const Mesh& pattern = worn_pattern(model, batch);
  if (pattern.has_uv()) out.uv = pattern.uv, out.uv_faces = pattern.uv_faces;
  out.vertices = moved_by.back(garment.mat(0).cast<double>());
  if (!out.vertices.allFinite()) throw Error("the model predicted a non-finite vertex");
  const geometry::BodySurface surface(body.vertices, body.faces);
  double p = geometry::penetration_ratio(surface, out.vertices);
  if (pushed_to >= 0) {
    // The garment's edges lifted too, its faces kept off the body's peaks,
    // and then its crossings of itself undone, each round's moves pushed out
    // again, as the models' push_out node does (geometry::GarmentClearance:
    // without the faces a heavy body's peaks stayed through the shirt, "6
    // body edges through the garment", and without the untangle a posed BMI
    // 50 body's shirt was left crossing itself at 13 edge-face pairs).
    geometry::GarmentClearanceOptions clearing;
    clearing.margin = pushed_to;
    geometry::GarmentClearance clearance(out.faces, out.num_vertices(), clearing);
    // The template: where two layers belong.
    const auto [pushed, untangled] = clearance.run(surface, out.vertices, &model.assets().garment->mesh.vertices);
    std::printf("pushed out: %d vertices moved (at most %.2f cm), from p = %.2f%% of them inside the body; the garment's "
                "crossings of itself undone: %d edge-face pairs before, %d after\n",
                pushed.moved, 100.0 * pushed.largest_move, 100.0 * p, untangled.crossings_before, untangled.crossings_after);
    p = geometry::penetration_ratio(surface, out.vertices);
  }
  write_mesh(vm["out"].as<std::string>(), out);
  // p counts vertices; an edge can pass through the body with both ends
  // outside (a thin body's ridge), so the crossings are counted too (exact
  // edge-triangle tests, code shared with no contact or push-out).
  const geometry::SurfaceCrossings crossings = geometry::surface_crossings(out.vertices, out.faces, body.vertices, body.faces);
  // And the cloth through itself, as simulate counts it (an outside check
  // found a sleeve crumpled through the shirt told "0 edges crossing it").
  const std::size_t self = geometry::self_edge_crossings(out.vertices, out.faces, geometry::kCrossingsCountedAtMost).size();
  // (One body, the first the model meets: the ms include building what the
  // nodes keep between bodies, several times a body's steady cost -- 50-85
  // ms against 3-5 -- which an outside check read as the model's speed.)
  std::printf("wrote %s: %d garment vertices predicted in %.2f ms (the first body, the model's setup included: drape "
              "bench infer times the steady ms per body); p = %.2f%% of them inside the body, %d edges crossing it, "
              "the garment through itself %zu edge-face pairs\n",
              vm["out"].as<std::string>().c_str(), out.num_vertices(), ms, 100.0 * p, crossings.total(), self);
  // (Printed, and on the picture: its caption said "p = 0.00%" beside a shirt
  // 32 edges through the body and through itself at 44, an outside check.)
  const auto warn = [&](const std::string& text) {
    std::cerr << text << "\n";
    notes.push_back(text);
  };
  if (self > 0)
    warn("warning: the garment passes through itself: " + std::to_string(self) +
         " pairs of an edge and a face it passes through (a fold or a sleeve the network drew through the cloth; the "
         "model's push-out untangles what it can, and a pose or body outside its training leaves more)");
  if (crossings.total() > 0)
    warn("warning: the garment and the body cross: " + std::to_string(crossings.garment_edges_through_body) +
         " garment edges through the body, " + std::to_string(crossings.body_edges_through_garment) +
         " body edges through the garment " +
         (pushed_to >= 0 ? "(left by --push-out: a larger clearance may clear them)"
                         : "(--push-out moves the garment off the body, when the model has no push-out or its own "
                           "could not)"));
  if (vm.count("svg")) {
    char caption[160];
    std::snprintf(caption, sizeof caption, "predicted in %.1f ms, p = %.2f%%, %d edges crossing the body, through itself %zu",
                  ms, 100.0 * p, crossings.total(), self);
    SvgFigure figure = drape_figure("drape predict: " + std::filesystem::path(model_file).filename().string() + " for " +
                                        asked_body_words(vm),
                                    caption, body, out);
    for (const std::string& note : notes) figure.add_note(note);
    figure.write(vm["svg"].as<std::string>());
    std::printf("wrote %s\n", vm["svg"].as<std::string>().c_str());
  }
  if (vm.count("body-out")) {
    write_mesh(vm["body-out"].as<std::string>(), body);
    std::printf("wrote %s\n", vm["body-out"].as<std::string>().c_str());
  }
  return 0;
}

const RegisterCommand registered{{"predict", "the garment a trained model predicts for a body (--body or --bmi)", run}};

}  // namespace
}  // namespace drape::cli
