#include "model_body.hpp"
#include "pose_options.hpp"

#include <drape/bodies/given_body.hpp>
#include <drape/bodies/limb_turns.hpp>
#include <drape/bodies/pose.hpp>
#include <drape/garment_sizes.hpp>
#include <drape/geometry/body_units.hpp>
#include <drape/io/checkpoint.hpp>
#include <drape/io/shipped_files.hpp>
#include <drape/scene/garment_size.hpp>
#include <drape/io/mesh_io.hpp>
#include <drape/scene/scene.hpp>
#include <drape/services/dataset_poses.hpp>
#include <drape/services/model_body.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <iostream>
#include <map>
#include <set>
#include <utility>

#include <yaml-cpp/yaml.h>

namespace drape::cli {

namespace fs = std::filesystem;

namespace {

ModelBodyInput body_input(const po::variables_map& vm) {
  if (vm.count("body") && (vm.count("height") || vm.count("sex") || vm.count("girth")))
    throw UsageError("--height, --sex and --girth go with --bmi; --body gives the body itself");
  ModelBodyInput input;
  if (vm.count("body")) {
    input.name = vm["body"].as<std::string>();
    const Mesh mesh = read_mesh(input.name);
    input.vertices = mesh.vertices;
    input.faces = mesh.faces;
  } else {
    BodyRequest request;
    request.bmi = vm["bmi"].as<double>();
    if (vm.count("height")) request.height = vm["height"].as<double>();
    // (NaN was "BMI nan is outside the reachable range", where drape body says what it is.)
    for (const auto& [option, value] : {std::pair{"--bmi", request.bmi}, std::pair{"--height", request.height}})
      if (!std::isfinite(value))
        throw UsageError(std::string(option) + " " + std::to_string(value) + ": not a finite number");
    if (vm.count("sex")) request.sex = vm["sex"].as<double>();
    request.proportions = parse_girths(vm);
    input.request = request;
  }
  if (vm.count("garment-size")) input.garment_size = vm["garment-size"].as<std::string>();
  if (vm.count("garment-grade")) input.garment_grade = vm["garment-grade"].as<double>();
  return input;
}

// The vertex count of the bodies a model file drapes, from its metadata and
// its body model alone (not its weights, assets or graph); -1 for a file
// that is no model this build reads.
Eigen::Index model_body_vertices(const Registry& registry, const fs::path& file) {
  try {
    const Checkpoint checkpoint = read_checkpoint(file);
    const auto assets = checkpoint.meta.find("assets");
    if (assets == checkpoint.meta.end()) return -1;
    return make_body_model(registry, parse_assets_spec(assets->second, file.string()))->num_vertices();
  } catch (const std::exception&) {
    return -1;  // not a model, or one this build cannot read: it takes no body here
  }
}

// The models in `model`'s folder whose body model makes bodies of `count`
// vertices, "tshirt-coarse.h5 and tshirt-coarse-regular.h5": for a body mesh
// of another rig or body model than the model's (a mannequin body given to
// the human rig's model). On the error's path only (each file is read).
std::string models_taking(const Model& model, Eigen::Index count, const po::variables_map& vm) {
  if (model.file().empty()) return "";
  const Registry& registry = Registry::load_default(plugin_path(vm));
  std::vector<std::string> found;
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(model.file().parent_path(), ec)) {
    if (entry.path().extension() != ".h5" || fs::equivalent(entry.path(), model.file(), ec)) continue;
    if (model_body_vertices(registry, entry.path()) == count) found.push_back(entry.path().filename().string());
  }
  std::sort(found.begin(), found.end());
  std::string names;
  for (std::size_t i = 0; i < found.size(); ++i)
    names += (i == 0 ? "" : i + 1 == found.size() ? " and " : ", ") + found[i];
  return names;
}

// The shipped scenes whose body model makes bodies of `count` vertices (a
// MakeHuman body given to the parametric body's model: no model drapes it,
// a scene of it simulates it), as "graphs/scenes/a.yaml, ..."; "" for none.
// Builds each scene's body model: the error's path only.
std::string scenes_taking(const Registry& registry, Eigen::Index count) {
  std::set<std::string> found;
  std::map<std::string, Eigen::Index> counts;  // by the scene's body model and its parameters
  for (const fs::path& root : shipped_data_dirs()) {
    std::error_code ec;
    for (const fs::directory_entry& entry : fs::directory_iterator(root / "graphs" / "scenes", ec)) {
      if (entry.path().extension() != ".yaml") continue;
      try {
        const Scene scene = load_scene(entry.path());
        std::string key = scene.body_model;
        for (const auto& [name, value] : scene.body_params) key += "," + name + "=" + YAML::Dump(value.node);
        auto it = counts.find(key);
        if (it == counts.end()) it = counts.emplace(key, make_scene_body_model(registry, scene)->num_vertices()).first;
        if (it->second == count) found.insert("graphs/scenes/" + entry.path().filename().string());
      } catch (const std::exception&) {
        // (a scene whose body model cannot be made here, MakeHuman's without its assets: not one that takes it)
      }
    }
    if (!found.empty()) break;
  }
  std::string names;
  for (const std::string& f : found) names += (names.empty() ? "" : ", ") + f;
  return names;
}

// Whether the body mesh of --body is posed (LimbFit::posed, against the mean
// body of `model_file`'s body model): the default model is then the one of
// posed drapes, which reads the pose off the mesh. Reads the model's
// metadata, not its weights; false whenever it cannot tell (the mesh's
// errors are reported where it is read for the prediction).
bool body_mesh_posed(const fs::path& model_file, const po::variables_map& vm) {
  if (!vm.count("body")) return false;
  try {
    const Checkpoint checkpoint = read_checkpoint(model_file);
    const auto assets = checkpoint.meta.find("assets");
    if (assets == checkpoint.meta.end()) return false;
    const auto body = make_body_model(Registry::load_default(plugin_path(vm)),
                                      parse_assets_spec(assets->second, model_file.string()));
    const Mesh mesh = read_mesh(vm["body"].as<std::string>());
    if (!body->poseable() || mesh.vertices.rows() != body->num_vertices()) return false;
    const Eigen::MatrixX3d mean = body->vertices(body->mean_shape());
    // A mesh in other units, or one the model's faces read wrong (mirrored,
    // re-indexed, spiked), has limbs that only look turned: not posed, and
    // refused by the model's own checks after this.
    check_body_units(mesh.vertices, "body");
    require_body_model_mesh(mesh.vertices, &mesh.faces, mean, body->faces(), "body");
    return !posed_in_words(mesh.vertices, *body, GivenBodyFrame(*body)).empty();
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace

void add_model_body_options(po::options_description& options, const std::string& body_help) {
  options.add_options()("body", po::value<std::string>(), body_help.c_str())(
      "strict", "refuse (exit 2) a body outside the model's training domain instead of warning")(
      "bmi", po::value<double>(), "or make the body with the model's body plugin: target BMI")(
      "height", po::value<double>(), "with --bmi: height in m (default 1.75)")(
      "sex", po::value<double>(), "with --bmi: 0 female ... 1 male (default 1)")(
      "garment-size", po::value<std::string>(),
      ("the garment's size: for a model of drapes in each body's own size, one of its sizes (drape model info lists "
       "them) or auto, the default: the size the tailor's rule gives the body (docs/garments.md); for a model trained "
       "on a few sizes: " + garment_size_choices()).c_str())(
      "garment-grade", po::value<double>(),
      "for a model of drapes in each body's own size: the garment's grade as a number (its girth over the design size's) "
      "instead of a size");
  add_girth_option(options, "with --bmi: ");
  options.add_options()(
      "pose", po::value<std::string>(),
      "for a model of posed drapes: the body's pose, name=degrees,... (docs/poses.md); the body given or made is "
      "taken as unposed")("pose-file", po::value<std::string>(), "the same from a YAML map of joint angle names to degrees")(
      "smpl-theta", po::value<std::string>(), "the same as SMPL's θ from a text file (SMPL body models)");
}

const Mesh& worn_pattern(const Model& model, const SampleBatch& batch) {
  if (!batch.garment_grade.empty() && model.garment_sizes()) {
    const GarmentSizes& sizes = *model.garment_sizes();
    if (const std::optional<std::size_t> size = sizes.find(batch.garment_grade(0, 0, 0))) return sizes.material(*size);
  }
  return model.assets().garment->mesh;
}

std::string asked_body_words(const po::variables_map& vm) {
  char bmi[32];
  if (vm.count("bmi")) std::snprintf(bmi, sizeof bmi, "BMI %g", vm["bmi"].as<double>());  // (18.75 was "18.7")
  std::string what = vm.count("bmi") ? std::string(bmi) : vm["body"].as<std::string>();
  char more[64];
  if (vm.count("bmi") && vm.count("height")) std::snprintf(more, sizeof more, ", %.2f m", vm["height"].as<double>()), what += more;
  if (vm.count("bmi") && vm.count("sex")) std::snprintf(more, sizeof more, ", sex %g", vm["sex"].as<double>()), what += more;
  if (vm.count("pose")) what += ", posed " + vm["pose"].as<std::string>();
  if (vm.count("pose-file")) what += ", posed by " + vm["pose-file"].as<std::string>();
  if (vm.count("smpl-theta")) what += ", posed by SMPL theta " + vm["smpl-theta"].as<std::string>();
  if (vm.count("garment-size")) what += ", size " + vm["garment-size"].as<std::string>();
  return what;
}

bool pose_given(const po::variables_map& vm) {
  return vm.count("pose") + vm.count("pose-file") + vm.count("smpl-theta") > 0;
}

std::string model_file_or_default(const po::variables_map& vm, bool posed_elsewhere) {
  if (vm.count("model")) return find_input_file(vm["model"].as<std::string>()).string();  // models/... from anywhere
  // A posed body goes to the shipped model of posed drapes (the A-pose model
  // refuses a pose); DRAPE_MODEL, when set, names the one model for both.
  const char* env = std::getenv("DRAPE_MODEL");
  const std::string file = default_model_path().string();
  if (!(env && *env) && (pose_given(vm) || posed_elsewhere || (!file.empty() && body_mesh_posed(file, vm))))
    if (const fs::path posed = shipped_model_path(posed_model_name); !posed.empty()) return posed.string();
  if (file.empty())
    throw UsageError(std::string("no --model given and the shipped model (models/") + kDefaultModelFile + ") was not found: give "
                     "--model FILE from drape train, or set DRAPE_MODEL");
  return file;
}

namespace {

// The shipped models of the two rigs, each beside its twin on the other
// (the human rig's, the defaults, and the mannequin's: docs/bodies.md).
constexpr std::pair<const char*, const char*> kRigTwins[] = {{kDefaultModelFile, "tshirt-coarse.h5"},
                                                             {posed_model_name, "tshirt-coarse-posed.h5"}};

// The shipped twin of model file `file` (same pose space, the other rig)
// when its body model makes bodies of `count` vertices and `file`'s does
// not; empty else. (A file unreadable here: the check after loading names
// the mismatch.)
std::string rig_twin(const Registry& registry, const fs::path& file, Eigen::Index count) {
  if (model_body_vertices(registry, file) == count) return "";
  const std::string name = file.filename().string();
  for (const auto& [a, b] : kRigTwins) {
    const std::string twin = name == a ? b : name == b ? a : "";
    if (twin.empty()) continue;
    const fs::path path = shipped_model_path(twin);
    if (!path.empty() && model_body_vertices(registry, path) == count) return path.string();
  }
  return "";
}

}  // namespace

std::string model_file_for_samples(const po::variables_map& vm, const Registry& registry, const DatasetReader& data,
                                   const std::vector<std::size_t>& indices) {
  std::string file = model_file_or_default(vm);
  const char* env = std::getenv("DRAPE_MODEL");
  if (vm.count("model") || (env && *env)) return file;
  const Model model = Model::load(registry, file);
  if (!data.layout().pose_angles.empty() && drapes_a_pose_only(model)) {
    const std::optional<std::string> posed = first_posed_sample(data, indices, model.body_model());
    if (const fs::path posed_model = shipped_model_path(posed_model_name); posed && !posed_model.empty()) {
      std::cerr << "note: " << *posed << ": draped by the shipped model of posed drapes, " << posed_model.string()
                << " (--model names another)\n";
      file = posed_model.string();
    }
  }
  // A dataset of the other rig's bodies (the mannequin's 6,490 vertices
  // under the human rig's default model): its twin there, said. (optimize
  // --data refused the README's own mannequin dataset, "but the template
  // has 991 and 6904", an outside check.)
  return model_file_for_rig(vm, registry, file, data.layout().body_vertices, data.name());
}

std::string model_file_for_rig(const po::variables_map& vm, const Registry& registry, const std::string& file,
                               Eigen::Index body_vertices, const std::string& what) {
  const char* env = std::getenv("DRAPE_MODEL");
  if (vm.count("model") || (env && *env)) return file;
  const std::string twin = rig_twin(registry, file, body_vertices);
  if (twin.empty()) return file;
  std::cerr << "note: " << what << " holds bodies of " << body_vertices << " vertices (another rig than "
            << fs::path(file).filename().string() << "'s): draped by the shipped " << twin
            << ", the model of that rig (--model names another)\n";
  return twin;
}

std::string model_file_for_body(const po::variables_map& vm, const Registry& registry, const std::string& file) {
  const char* env = std::getenv("DRAPE_MODEL");
  if (!vm.count("body") || vm.count("model") || (env && *env)) return file;
  Eigen::Index count = 0;
  try {
    count = read_mesh(vm["body"].as<std::string>()).num_vertices();
  } catch (const std::exception&) {
    return file;  // (read again with the model, which says what is wrong with it)
  }
  std::string twin = rig_twin(registry, file, count);
  if (twin.empty()) return file;
  // A posed body of the other rig: that rig's model of posed drapes (its
  // A-pose model would drape it warning that it looks posed).
  if (fs::path(twin).filename() == "tshirt-coarse.h5" && !pose_given(vm) && body_mesh_posed(twin, vm))
    if (const fs::path posed = shipped_model_path(posed_model_name); !posed.empty())
      if (const std::string posed_twin = rig_twin(registry, posed, count); !posed_twin.empty()) twin = posed_twin;
  std::cerr << "note: the body " << vm["body"].as<std::string>() << " has " << count << " vertices (another rig than "
            << fs::path(file).filename().string() << "'s): draped by the shipped " << twin
            << ", the model of that rig (--model names another)\n";
  return twin;
}

SampleBatch model_body(const Model& model, const po::variables_map& vm, BodyMove* moved_by,
                       std::vector<std::string>* printed, const Pose* fallback_pose, const std::string& fallback_source,
                       bool refuse_crossing, bool announce) {
  ModelBodyInput input = body_input(vm);
  // A body far from the origin (a scene's or a survey's coordinates) moved
  // near it in double before the network's single precision rounds it: at
  // 1e6 m a float holds a coordinate to 6 cm, and an outside check's body
  // there was draped 3-12 cm off and through itself, its size misread.
  // The drape is moved back with the body (the composed move below).
  BodyMove near_origin;
  // (A body in other units, millimetres, is no far body: the units check refuses it, without this note first.)
  const auto body_sized = [](const Eigen::MatrixX3d& v) {
    return (v.colwise().maxCoeff() - v.colwise().minCoeff()).maxCoeff() <= 2 * HeightRange::max;
  };
  if (input.vertices && input.vertices->allFinite() && input.vertices->cwiseAbs().maxCoeff() > kFloatExactReach &&
      body_sized(*input.vertices)) {
    // Whole kilometres: what is left is within 500 m on each axis (0.015 mm
    // in a float), and an axis the body stands well on keeps its place.
    near_origin.offset = (input.vertices->colwise().mean().array() / kFloatExactReach).round().matrix() * kFloatExactReach;
    *input.vertices = near_origin.placed(*input.vertices);
    char note[256];
    std::snprintf(note, sizeof note,
                  "note: the body stands %.0f m from the origin; it is draped moved near it in double precision (the "
                  "network's single precision holds coordinates that far only to %.1f mm) and the drape moved back",
                  near_origin.offset.norm(), 1e3 * float_rounding(near_origin.offset.cwiseAbs().maxCoeff()));
    std::cerr << note << "\n";
    if (printed) printed->push_back(note);
  }
  SampleBatch batch;
  try {
    batch = model_body_batch(model, input);
  } catch (const ConfigError& e) {
    // A mesh of another vertex count: say which models beside this one take it.
    if (!input.vertices || input.vertices->rows() == model.assets().body.num_vertices()) throw;
    const std::string others = models_taking(model, input.vertices->rows(), vm);
    if (others.empty()) {
      const std::string scenes = scenes_taking(Registry::load_default(plugin_path(vm)), input.vertices->rows());
      if (scenes.empty()) throw;
      throw ConfigError(std::string(e.what()) + "; no shipped model drapes bodies of " +
                        std::to_string(input.vertices->rows()) + " vertices, the body model of " + scenes +
                        " makes them: drape simulate SCENE --body simulates the garment on it");
    }
    throw ConfigError(std::string(e.what()) + "; " + others + " beside " + model.file().filename().string() +
                      " take bodies of " + std::to_string(input.vertices->rows()) + " vertices (--model)");
  }
  const BodyPreparation preparation(model, read_domain(model.file()));
  PreparedBodies prepared =
      preparation.prepare(batch, vm.count("strict") > 0, "--strict", true, vm.count("body") > 0, pose_given(vm));
  // Posed after the body is measured and placed at rest (a raised arm is no girth).
  std::optional<Pose> pose = pose_options(vm, model.body_model(), model.assets_spec().body_model);
  // The fallback (a scene's pose) where no option gives one: a drape
  // optimised on the unposed body while the scene named a pose was measured
  // p = 0 against a body the user never asked for (an outside check: 109
  // vertices inside the scene's posed body).
  bool fallen_back = false;
  if (!pose && fallback_pose && !fallback_pose->empty()) {
    if (prepared.given_posed(0)) {
      prepared.notices.push_back({Notice::Level::note, "the body mesh is posed: it is draped in its own pose, not in " +
                                                           fallback_source + "'s (" + format_pose(*fallback_pose) + ")"});
    } else {
      pose = *fallback_pose, fallen_back = true;
      prepared.notices.push_back({Notice::Level::note, "the body is posed as " + fallback_source + " sets: " +
                                                           format_pose(*fallback_pose) + " (--pose replaces it)"});
    }
  }
  try {
    for (Notice& n : preparation.pose(batch, pose ? *pose : Pose{}, vm.count("strict") > 0, "--strict", &prepared, true,
                                      refuse_crossing))
      prepared.notices.push_back(std::move(n));
  } catch (const ConfigError& e) {
    if (!fallen_back) throw;
    throw ConfigError(fallback_source + " poses the body (" + format_pose(*pose) + "): " + e.what());
  }
  for (const Notice& n : prepared.notices) {
    if (!announce) break;
    const std::string line = (n.level == Notice::Level::note ? "note: " : "warning: ") + n.text;
    std::cerr << line << "\n";
    if (printed) printed->push_back(line);
  }
  if (moved_by) *moved_by = near_origin.then(prepared.moved_by.front());
  return batch;
}

}  // namespace drape::cli
