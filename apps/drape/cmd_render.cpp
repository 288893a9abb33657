// `drape render`: a picture of a body and its drape to look at -- a
// self-contained HTML page with a 3D viewer (drag to turn), or an SVG front
// view -- with the garment coloured by its distance to the body, its error
// against the simulated drape, or its strain against the material space.
// The garment is a model's prediction (default: the shipped model), a mesh, or a
// dataset's simulated drape (--data ... --simulated).
#include "command.hpp"

#include <drape/assets/dataset_assets.hpp>
#include <drape/garment_sizes.hpp>
#include <drape/io/dataset.hpp>
#include <drape/geometry/body_units.hpp>
#include <drape/geometry/surface_crossings.hpp>
#include <drape/geometry/self_intersection.hpp>
#include <drape/geometry/closest_point.hpp>
#include <drape/geometry/penetration.hpp>
#include <drape/io/mesh_io.hpp>
#include <drape/training/model.hpp>
#include <drape/registry.hpp>
#include <drape/io/svg_figure.hpp>
#include <drape/services/dataset_poses.hpp>
#include <drape/services/model_body.hpp>
#include <drape/services/worn_garments.hpp>
#include <drape/training/metrics.hpp>

#include "model_body.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <vector>

namespace drape::cli {
namespace DRAPE_UNITY_ID {  // the anonymous namespace, or a unique one in a unity build (command.hpp)

// Per vertex: the mean relative length change (%) of its edges against their
// lengths in the material space (face_edge_rest_lengths: face by face, in metres).
Eigen::VectorXd edge_strain_percent(const Mesh& garment, const std::vector<double>& rest_lengths) {
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(garment.num_vertices()), count = sum;
  for (int f = 0; f < garment.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = garment.faces(f, k), b = garment.faces(f, (k + 1) % 3);
      const double rest = rest_lengths[static_cast<std::size_t>(3 * f + k)];
      if (!(rest > 0)) continue;
      const double strain = 100.0 * std::abs((garment.vertices.row(b) - garment.vertices.row(a)).norm() / rest - 1.0);
      for (int v : {a, b}) {
        sum(v) += strain;
        count(v) += 1;
      }
    }
  return sum.cwiseQuotient(count.cwiseMax(1.0));
}

// A garment file's vertices within reach of the body it is drawn on: a
// vertex at 1e39 m (infinite in the page's float32) drew a squashed picture
// captioned "p = 0.10 %", exit 0 (an outside check). 10 m beyond the body's
// box is no garment of it (other units, or a damaged file).
void check_garment_near_body(const Eigen::MatrixX3d& garment, const Eigen::MatrixX3d& body, const std::string& file) {
  constexpr double kReach = 10.0;  // m
  const Eigen::RowVector3d lo = body.colwise().minCoeff(), hi = body.colwise().maxCoeff();
  for (Eigen::Index v = 0; v < garment.rows(); ++v) {
    const Eigen::RowVector3d outside = (lo - garment.row(v)).cwiseMax(garment.row(v) - hi).cwiseMax(0.0);
    if (!(outside.norm() <= kReach)) {
      char text[200];
      std::snprintf(text, sizeof text, ": vertex %ld lies %.3g m from the body's bounding box (at most %g m for a garment "
                    "on it): another unit, or a damaged file", static_cast<long>(v), outside.norm(), kReach);
      throw ConfigError(file + text);
    }
  }
}

// The rest lengths the strain is measured against (face_edge_rest_lengths):
// the pattern of the garment the body wears. A sample of a dataset made in
// each body's own size wore its size (worn_garments); a model of drapes in
// each body's own size dresses the body in the size of the grade it was fed
// (its size chart's); else the template's.
std::vector<double> worn_rest_lengths(const Registry& registry, const Mesh& template_mesh, const DatasetReader* reader,
                                      std::size_t sample, const Model* model, const SampleBatch* batch) {
  if (!template_mesh.has_uv()) throw ConfigError("--colour strain needs the template's material space (UVs); it has none");
  if (reader) {
    const WornGarments worn = worn_garments(registry, *reader, {sample});
    if (const std::vector<double>* rest = worn.rest_of(0)) return *rest;
  } else if (model && batch) {
    return face_edge_rest_lengths(worn_pattern(*model, *batch));  // the size the push-out held the prediction to
  }
  return face_edge_rest_lengths(template_mesh);
}

// The page or picture: the garment on the body, coloured by its distance to
// the body, its error against `truth`, or its strain against the material
// space of the garment the body wears (worn_rest_lengths).
void draw(const po::variables_map& vm, const std::string& colour, const std::string& what,
          const std::vector<std::string>& notes, const Mesh& body, const Mesh& garment, const Mesh& truth,
          const std::vector<double>& rest_lengths) {
  SvgFigure figure("drape render: " + what);
  for (const std::string& note : notes) figure.add_note(note);
  const geometry::BodySurface surface(body.vertices, body.faces);
  const double p = geometry::penetration_ratio(surface, garment.vertices);
  Eigen::VectorXd values;
  SvgColourScale scale;
  char caption[256];
  if (colour == "distance") {
    values = 100.0 * surface.signed_distances(garment.vertices);
    scale = clearance_scale();  // (inside the body: its own colour, as every drape picture's)
    std::snprintf(caption, sizeof caption, "p = %.2f%% of the vertices inside the body", 100.0 * p);
  } else if (colour == "error") {
    values = 100.0 * (garment.vertices - truth.vertices).rowwise().norm();
    scale = {"distance to the simulated garment (cm)", 0.0, 2.0};
    std::snprintf(caption, sizeof caption, "ME %.2f cm, max %.2f cm, p = %.2f%%", values.mean(), values.maxCoeff(), 100.0 * p);
  } else {
    values = edge_strain_percent(garment, rest_lengths);
    // Per vertex, and unsigned: said on the legend and in the caption (an
    // outside check read the max as the most strained edge, which eval's
    // strain_max is; a torn edge is averaged with its neighbours here).
    scale = {"mean |edge length change| at each vertex, against the material space (%)", 0.0, 10.0};
    std::snprintf(caption, sizeof caption, "mean strain %.2f%%, max %.2f%% (vertex means of |edge length change|), p = %.2f%%",
                  values.mean(), values.maxCoeff(), 100.0 * p);
  }
  // What p leaves out, as predict and simulate count it: edges through the
  // body with both ends outside, and the cloth through itself.
  const int crossing = geometry::surface_crossings(garment.vertices, garment.faces, body.vertices, body.faces).total();
  const std::size_t self = geometry::self_edge_crossings(garment.vertices, garment.faces, geometry::kCrossingsCountedAtMost).size();
  const std::string counted = std::string(caption) + ", " + std::to_string(crossing) + " edges crossing the body, " +
                              std::to_string(self) + " edge-face pairs of the garment through itself";
  std::snprintf(caption, sizeof caption, "%s", counted.c_str());
  figure.add_panel(drape_panel(caption, body, garment, std::move(values)));
  figure.set_colour_scale(scale);
  figure.write(vm["out"].as<std::string>());
  std::printf("wrote %s (%s; %s)\n", vm["out"].as<std::string>().c_str(), what.c_str(), caption);
}

// --sample as an index (a long, so that -1 is refused instead of wrapping to 2^64 - 1).
std::size_t sample_index(const po::variables_map& vm) {
  const long i = vm["sample"].as<long>();
  if (i < 0) throw UsageError("--sample " + std::to_string(i) + ": a sample index is 0 or more");
  return static_cast<std::size_t>(i);
}

// --data FILE --sample I --simulated: the dataset's drape on its body, on the
// template of the scene the dataset records.
int render_simulated(Registry& registry, const po::variables_map& vm, const std::string& colour) {
  const std::string data = vm["data"].as<std::string>();
  const DatasetReader reader(data);
  const std::size_t i = sample_index(vm);
  if (i >= reader.size()) throw UsageError("--sample " + std::to_string(i) + ": the dataset has " + std::to_string(reader.size()) + " samples");
  const auto assets = assets_for_dataset(registry, reader, data, 1000, default_cache_dir());
  Mesh body;
  body.faces = assets->body.faces;
  body.vertices = reader.body_vertices({i}).mat(0).cast<double>();
  Mesh garment = assets->garment->mesh;
  garment.vertices = reader.garment_vertices({i}).mat(0).cast<double>();
  const std::string what = "simulated drape, sample " + std::to_string(i) + " of " + std::filesystem::path(data).filename().string();
  draw(vm, colour, what, {}, body, garment, garment,
       colour == "strain" ? worn_rest_lengths(registry, assets->garment->mesh, &reader, i, nullptr, nullptr) : std::vector<double>());
  return 0;
}

int run(const std::vector<std::string>& args) {
  po::options_description opts("drape render");
  opts.add_options()("model", po::value<std::string>(), "model file (default: the shipped model); its template gives the faces (--simulated draws on the dataset's own template, no model)")(
      "garment", po::value<std::string>(),
      "draw this garment mesh instead of a prediction: the model's template topology, or with --body any garment "
      "(a mesh garment simulate wrote, on its --body-out), drawn as the files give them and coloured by distance")(
      "data", po::value<std::string>(), "or take body (and the simulated garment, for --colour error) from a dataset")(
      "sample", po::value<long>()->default_value(0), "with --data: the sample index")(
      "simulated", "with --data: draw the dataset's simulated garment instead of a prediction")(
      "colour", po::value<std::string>()->default_value("distance"),
      "distance (to the body, cm) | error (to the simulated garment of --data, cm) | strain (edge length change, %)")(
      "out", po::value<std::string>(), "picture to write: .html (3D viewer) or .svg (front view)");
  add_model_body_options(opts, "body mesh in the model's body topology");
  po::variables_map vm;
  const std::string usage =
      "drape render [--model model.h5] (--bmi 35 | --body body.obj | --data data.h5 --sample I [--simulated]) [--garment g.obj] "
      "[--colour distance|error|strain] --out drape.html";
  if (!parse(usage, args, opts, {}, vm)) return 0;
  if (!vm.count("out")) throw UsageError("--out FILE is required (.html or .svg)");
  const std::string ext = std::filesystem::path(vm["out"].as<std::string>()).extension().string();
  if (ext != ".html" && ext != ".htm" && ext != ".svg") throw UsageError("--out must end in .html or .svg");
  if (vm.count("body") + vm.count("bmi") + vm.count("data") != 1)
    throw UsageError("give the body exactly one way: --bmi X, --body FILE or --data FILE --sample I");
  const std::string colour = vm["colour"].as<std::string>();
  if (colour != "distance" && colour != "error" && colour != "strain")
    throw UsageError("--colour must be distance, error or strain, got '" + colour + "'");
  if (colour == "error" && !vm.count("data"))
    throw UsageError("--colour error compares with a simulated drape: give --data FILE --sample I");
  if (!vm.count("data") && !vm["sample"].defaulted())
    throw UsageError("--sample picks a sample of --data FILE; a body given by --bmi or --body has none");
  // A dataset's sample is its own body and pose: a body option beside --data was ignored without a word.
  if (vm.count("data"))
    for (const char* option : {"height", "sex", "girth", "pose", "pose-file", "smpl-theta", "smpl", "garment-size", "garment-grade"})
      if (vm.count(option) && !vm[option].defaulted())
        throw UsageError(std::string("--") + option + " describes a body given by --bmi or --body; a sample of --data "
                         "has its own body, pose and garment: leave --" + option + " out");
  if (vm.count("simulated") && (!vm.count("data") || vm.count("garment")))
    throw UsageError("--simulated draws a dataset's own drape: give --data FILE --sample I, and no --garment");
  if (vm.count("simulated") && colour == "error")
    throw UsageError("--colour error compares a prediction with the dataset's simulated drape; --simulated draws that "
                     "drape itself (its error is 0): leave one out");
  Registry& registry = Registry::load_default(plugin_path(vm));
  // A dataset's own drape is drawn on its own template (the scene it
  // records: the human rig's drapes on the human rig's body), no model needed.
  if (vm.count("simulated")) return render_simulated(registry, vm, colour);
  // A dataset's posed body goes to the model of posed drapes, as a posed --body does.
  std::optional<DatasetReader> data;
  if (vm.count("data")) {
    data.emplace(vm["data"].as<std::string>());
    if (sample_index(vm) >= data->size())
      throw UsageError("--sample " + std::to_string(sample_index(vm)) + ": the dataset has " + std::to_string(data->size()) + " samples");
  }
  const std::string model_file =
      data ? model_file_for_samples(vm, registry, *data, {sample_index(vm)}) : model_file_for_body(vm, registry, model_file_or_default(vm));
  Model model = Model::load(registry, model_file);
  std::vector<std::string> notes;  // what model_body printed, shown on the page too
  SampleBatch batch;
  Mesh truth;
  std::string what;
  // A body given standing elsewhere or turned is drawn as given: its drape
  // predicted where (and as) the training bodies stood and moved back, a
  // --garment file (written by predict where the body was) drawn as it is.
  BodyMove moved_by;
  // A garment of another topology than the model's template on a body mesh
  // (a user's mesh garment simulate wrote, on its --body-out): drawn as the
  // files give them. It was refused ("has 2136 vertices, but the model's
  // garment template has 991"), and simulate --svg was the only picture.
  if (vm.count("garment") && vm.count("body")) {
    const std::string garment_file = vm["garment"].as<std::string>(), body_file = vm["body"].as<std::string>();
    const Mesh given = read_mesh(garment_file);
    // A cut-short file (vertices, no faces) drew the body alone, "p = 0.00%".
    if (given.num_faces() == 0) throw ConfigError(garment_file + ": has no faces to draw or measure");
    if (given.num_vertices() != model.assets().garment->mesh.num_vertices()) {
      if (colour != "distance")
        throw UsageError("--colour " + colour + " compares with the model's template or a dataset's drape; " +
                         garment_file + " is another garment (" + std::to_string(given.num_vertices()) +
                         " vertices), drawn as it is: --colour distance");
      const Mesh body = read_mesh(body_file);
      if (body.num_faces() == 0) throw ConfigError(body_file + ": has no faces to draw or measure against");
      check_body_units(body.vertices, "body " + body_file);
      check_garment_near_body(given.vertices, body.vertices, garment_file);
      draw(vm, colour, garment_file + " on " + body_file, {}, body, given, given, {});
      return 0;
    }
  }
  if (data) {
    const DatasetReader& reader = *data;
    check_dataset_template(reader, vm["data"].as<std::string>(), model.assets());
    const std::size_t i = sample_index(vm);
    check_model_takes_dataset_poses(model, reader, {i});
    batch = read_samples(reader, {i}, model.graph(), false);
    truth = model.assets().garment->mesh;
    truth.vertices = reader.garment_vertices({i}).mat(0).cast<double>();
    what = "sample " + std::to_string(i) + " of " + std::filesystem::path(vm["data"].as<std::string>()).filename().string();
  } else {
    // A --garment file is drawn, not predicted: what model_body says of a
    // prediction (its size, a size the model did not learn, the domain) is
    // not said (an outside check was warned "the prediction may be wrong").
    batch = model_body(model, vm, &moved_by, &notes, nullptr, "", false, !vm.count("garment"));
    what = asked_body_words(vm);  // the page's title says which body: its height, sex and pose as asked
  }
  Mesh body;
  body.faces = model.assets().body.faces;
  body.vertices = moved_by.back(batch.body.mat(0).cast<double>());
  Mesh garment = model.assets().garment->mesh;
  std::vector<double> own_rest_lengths;  // a --garment file's strain against its own UVs
  if (vm.count("garment")) {
    const Mesh given = read_mesh(vm["garment"].as<std::string>());
    if (given.num_vertices() != garment.num_vertices())
      throw ConfigError(vm["garment"].as<std::string>() + " has " + std::to_string(given.num_vertices()) +
                        " vertices, but the model's garment template has " + std::to_string(garment.num_vertices()));
    // A file's UVs are its material space (simulate and predict write the
    // size worn): a drape simulated in size large was measured against the
    // size the tailor's rule gives the body, 8 % strained where it was at
    // rest. --garment-size or --garment-grade still names the pattern.
    if (colour == "strain" && given.has_uv() && given.faces == garment.faces && !vm.count("garment-size") &&
        !vm.count("garment-grade")) {
      own_rest_lengths = face_edge_rest_lengths(given);
      notes.push_back("strain against " + vm["garment"].as<std::string>() + "'s own UVs (its material space; " +
                      "--garment-size names a size's pattern instead)");
      std::fprintf(stderr, "note: %s\n", notes.back().c_str());
    } else if (colour == "strain") {
      notes.push_back(vm.count("garment-size") || vm.count("garment-grade")
                          ? "strain against the pattern of the size asked for"
                          : "strain against the pattern of the size the tailor's rule gives this body (" +
                                vm["garment"].as<std::string>() +
                                " carries no UVs on the template's faces; --garment-size names another size)");
      std::fprintf(stderr, "note: %s\n", notes.back().c_str());
    }
    check_garment_near_body(given.vertices, body.vertices, vm["garment"].as<std::string>());
    garment.vertices = given.vertices;
    what = vm["garment"].as<std::string>() + " on " + what;
  } else {
    garment.vertices = moved_by.back(model.predict(batch).mat(0).cast<double>());
    what = "prediction of " + std::filesystem::path(model_file).filename().string() + " for " + what;
  }

  draw(vm, colour, what, notes, body, garment, truth,
       colour != "strain"          ? std::vector<double>()
       : !own_rest_lengths.empty() ? own_rest_lengths
                                   : worn_rest_lengths(registry, model.assets().garment->mesh, data ? &*data : nullptr,
                                                       sample_index(vm), &model, &batch));
  return 0;
}

const RegisterCommand registered{
    {"render", "a picture of a body and its drape: HTML 3D viewer or SVG, coloured by distance, error or strain", run}};

}  // namespace
}  // namespace drape::cli
