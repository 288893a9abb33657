// Bodies and plugins: drape.body(bmi=..., height=..., sex=..., **girths),
// drape.BodyModel (any body plugin by name), drape.plugins(), drape.load_plugins().
#include "common.hpp"

#include <drape/bodies/posed_body.hpp>

#include <drape/bodies/body.hpp>
#include <drape/bodies/given_body.hpp>
#include <drape/geometry/body_units.hpp>
#include <drape/errors.hpp>
#include <drape/io/shipped_files.hpp>
#include <drape/nn/gemm.hpp>
#include <drape/params.hpp>
#include <drape/services/model_body.hpp>

#include <yaml-cpp/yaml.h>

#include <memory>
#include <optional>

namespace drape::python {
namespace {

ParamValues plugin_params(const py::dict& params, const std::string& what) {
  ParamValues values;
  for (const auto& [key, value] : params) {
    // YAML reads Python's str() of numbers, booleans and paths the way a scene file would.
    const std::string text = py::isinstance<py::bool_>(value) ? (value.cast<bool>() ? "true" : "false")
                                                               : py::str(value).cast<std::string>();
    values[key.cast<std::string>()] = {YAML::Load(text), {what, 0}};
  }
  return values;
}

class PyBodyModel {
 public:
  PyBodyModel(const std::string& name, const py::dict& params) : name_(name) {
    const PluginDescriptor& d = registry().get(name);
    if (!d.create_body) throw ConfigError("body model '" + name + "': the plugin is a " + d.kind + ", not a body model");
    model_ = registry().create_body(name, Params(d.params, plugin_params(params, "drape.BodyModel"), "body " + name));
    frame_.emplace(*model_);
  }

  const std::string& name() const { return name_; }
  std::vector<std::string> shape_names() const { return model_->shape_names(); }

  // The shape vector that reaches the request with the named proportions (girths) held, as drape body --girth.
  Eigen::VectorXd solve(const py::handle& bmi, const py::handle& height, const py::handle& sex, const py::dict& girths) const {
    const BodyRequest request = body_request(bmi, height, sex, girths, name_);
    py::gil_scoped_release release;
    return model_->solve(request);  // ConfigError naming the proportions the model takes, or their range
  }

  Eigen::MatrixX3d vertices(const py::handle& shape_arg) const {
    // c_style: a strided view (shape[::2], shape[::-1]) is copied, not read as if contiguous.
    // Real numbers only: a complex array's imaginary part was dropped without a word.
    const py::array given = py::array::ensure(shape_arg);
    const char kind = given ? given.dtype().kind() : 'O';
    auto shape = kind == 'f' || kind == 'i' || kind == 'u'
                     ? py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(given)
                     : py::array_t<double, py::array::c_style | py::array::forcecast>();
    const auto n = static_cast<py::ssize_t>(model_->shape_names().size());
    if (!shape || shape.ndim() != 1 || shape.shape(0) != n)
      throw ConfigError("shape: expected a float array of shape [" + std::to_string(n) + "] (" + name_ +
                            "'s shape parameters, BodyModel.shape_names)");
    Eigen::VectorXd s = Eigen::Map<const Eigen::VectorXd>(shape.data(), n);
    py::gil_scoped_release release;
    return model_->vertices(s);
  }

  // The pose read off a body mesh given posed and the mesh at rest, as drape
  // body --unpose (given_body.hpp): {"pose": {name: degrees}, "rest": float64
  // [N, 3] where and as the mesh stood, "shape", "fit_rms", "fit_max",
  // "reposed_error" (m), "notes": [str]}.
  py::dict unpose(const py::handle& mesh) const {
    // A float array (integer vertices were read on and refused as "not in the
    // body model's order").
    const auto n = static_cast<int>(model_->num_vertices());
    Eigen::MatrixX3d body = vertices_arg(mesh, "body_vertices", n);
    if (!model_->poseable())
      throw ConfigError("body_vertices: body " + name_ + " has no skeleton, so no pose can be read off a mesh");
    GivenPosedBody read;
    {
      py::gil_scoped_release release;
      check_body_units(body, "body_vertices");
      require_body_model_mesh(body, nullptr, frame_->mean(), model_->faces(), "body_vertices");  // re-indexed, spiked, mirrored
      read = unpose_given_body(body, *model_, *frame_, "body_vertices");
    }
    if (!read.outside.empty()) throw ConfigError(read.outside);
    py::dict pose;
    for (const auto& [angle, degrees] : read.fit.pose.angles) pose[py::str(angle)] = degrees;
    py::list notes;
    for (const std::string* note : {&read.turned, &read.pose_note, &read.warning})
      if (!note->empty()) notes.append(*note);
    if (read.lean_degrees > kLeanToleranceDegrees)
      notes.append("the mesh stands " + std::to_string(static_cast<int>(std::lround(read.lean_degrees))) +
                   " degrees from upright as a whole (lying, or upside down); rest is given as it stood");
    py::dict out;
    out["pose"] = pose;
    out["rest"] = to_numpy(read.moved.back(body));
    out["shape"] = to_numpy(Eigen::VectorXd(read.fit.shape));
    out["fit_rms"] = read.fit.fit_rms;
    out["fit_max"] = read.fit.fit_max;
    out["reposed_error"] = read.fit.reposed_error;
    out["notes"] = notes;
    return out;
  }

  const BodyModel& model() const { return *model_; }

 private:
  std::string name_;
  std::unique_ptr<BodyModel> model_;
  std::optional<GivenBodyFrame> frame_;  // the mean body, anchor and limbs, found on first use
};

}  // namespace

void register_bodies(py::module_& m) {
  py::class_<PyBodyModel>(m, "BodyModel",
                          "A body plugin (parametric, makehuman, smpl, ...): fixed topology, watertight, A-pose, metres, Y up.")
      .def(py::init<const std::string&, const py::dict&>(), py::arg("name") = "parametric", py::arg("params") = py::dict(),
           "The body plugin `name` with its plugin parameters (e.g. {'file': 'smpl.h5'} for smpl).")
      .def_property_readonly("name", &PyBodyModel::name)
      .def_property_readonly("shape_names", &PyBodyModel::shape_names, "names of the shape parameters, in vector order")
      .def_property_readonly("mean_shape", [](const PyBodyModel& b) { return to_numpy(b.model().mean_shape()); })
      .def_property_readonly("bmi_range", [](const PyBodyModel& b) { return b.model().bmi_range(); })
      .def_property_readonly("proportions", [](const PyBodyModel& b) {
             py::dict d;
             for (const auto& p : b.model().proportions()) d[py::str(p.name)] = py::make_tuple(p.min, p.max);
             return d;
           }, "{name: (min, max)}: the proportions (girths) a body request may hold")
      .def_property_readonly("vertex_count", [](const PyBodyModel& b) { return b.model().num_vertices(); })
      .def_property_readonly("faces", [](const PyBodyModel& b) { return to_numpy(Eigen::MatrixX3i(b.model().faces())); },
                             "int32 [F, 3], counter-clockwise seen from outside")
      .def(
          "solve",
          [](const PyBodyModel& b, const py::handle& bmi, const py::handle& height, const py::handle& sex, const py::kwargs& girths) {
            return to_numpy(b.solve(bmi, height, sex, girths));
          },
          py::arg("bmi") = 24.0, py::arg("height") = 1.75, py::arg("sex") = 1.0,
          "Shape parameters reaching the BMI, height and sex with the keyword proportions (girths) held.")
      .def("vertices", [](const PyBodyModel& b, const py::handle& shape) { return to_numpy(b.vertices(shape)); },
           py::arg("shape"), "float64 [N, 3] vertices of a shape vector")
      .def("unpose", &PyBodyModel::unpose, py::arg("body_vertices"),
           "The pose read off a body mesh [N, 3] given posed and the mesh at rest, as drape body --unpose: a dict of "
           "'pose' ({angle: degrees}), 'rest' (float64 [N, 3], where and as the mesh stood), 'shape' (the body model's "
           "shape fitted beside it), 'fit_rms' and 'fit_max' (m: the body model so posed against the mesh), "
           "'reposed_error' (m: the rest posed again against the mesh) and 'notes' (docs/poses.md, \"A body given "
           "posed\"). About a second; the GIL is released.");

  m.def(
      "body",
      [](const py::handle& bmi, const py::handle& height, const py::handle& sex, const std::string& model, const py::dict& params, const py::handle& pose,
         const py::kwargs& girths) {
        PyBodyModel b(model, params);
        // (pose= was read as a girth named "pose": "expected a number (a proportion ...)", an outside check.)
        const std::optional<Pose> posed = pose_arg(b.model(), model, pose);
        const Eigen::VectorXd shape = b.solve(bmi, height, sex, girths);
        Eigen::MatrixX3d v;
        {
          py::gil_scoped_release release;
          v = posed ? pose_body(b.model(), model, shape, *posed) : b.model().vertices(shape);
        }
        return py::make_tuple(to_numpy(std::move(v)), to_numpy(Eigen::MatrixX3i(b.model().faces())));
      },
      py::arg("bmi") = 24.0, py::arg("height") = 1.75, py::arg("sex") = 1.0, py::kw_only(), py::arg("model") = "parametric",
      py::arg("params") = py::dict(), py::arg("pose") = py::none(),
      "(vertices float64 [N, 3], faces int32 [F, 3]) of a body of that BMI, height (m) and sex (0 female ... 1 male)\n"
      "from a body plugin. Other keywords are proportions held while the BMI is reached, as drape body --girth\n"
      "(the parametric model's girths: chest, waist, belly, hips, arms, thighs, log factors in [-0.15, 0.15]).\n"
      "pose: joint angles in degrees ({'shoulder_abduction': 40} or 'shoulder_abduction=40,...'), as drape body --pose:\n"
      "the body posed by its skeleton; a pose in which it passes through itself raises ValueError naming the joints.");

  m.def(
      "plugins",
      []() {
        py::list out;
        for (const PluginDescriptor* d : registry().all()) {
          py::dict p;
          p["name"] = d->name;
          p["kind"] = d->kind;
          p["file"] = d->file;
          out.append(p);
        }
        return out;
      },
      "Every plugin loaded: dicts of name, kind and file (as `drape plugins`).");
  m.def(
      "load_plugins",
      [](const std::string& path) {
        // Asked for by name, so a folder that is not there or a file that is
        // no plugin is an error (--plugin-path and $DRAPE_PLUGIN_PATH only
        // warn: a stale entry must not stop every command), and so is a
        // plugin file refused (another ABI, missing symbols).
        const std::filesystem::path p(path);
        std::error_code ec;
        if (!std::filesystem::exists(p, ec))
          throw ConfigError("load_plugins: " + path + ": no such folder or file");
        const std::size_t refused_before = registry().refused().size();
        if (!std::filesystem::is_directory(p, ec)) {
          const std::string name = p.filename().string();
          if (!(name.rfind("libdrape_plugin_", 0) == 0 && p.extension() == ".so"))
            throw ConfigError("load_plugins: " + path + ": not a folder nor a plugin file (libdrape_plugin_<name>.so)");
        }
        registry().load_path({p});
        if (registry().refused().size() > refused_before && !std::filesystem::is_directory(p, ec))
          throw ConfigError("load_plugins: refused " + registry().refused().back());
      },
      py::arg("path"),
      "Loads the plugins of a folder (or one plugin file, libdrape_plugin_<name>.so), as --plugin-path does; "
      "ConfigError when the path does not exist, is no plugin file, or the one file given is refused (a "
      "plugin refused in a folder is a DrapeWarning, as with --plugin-path).");
  m.def("blas_corename", []() { return std::string(nn::blas_corename()); },
        "The kernel set OpenBLAS chose for this process ('' for another BLAS), e.g. 'Prescott' or 'SkylakeX'.");
  m.def(
      "better_blas_coretype",
      []() -> std::optional<std::string> {
        const char* c = nn::better_blas_coretype();
        return c ? std::optional<std::string>(c) : std::nullopt;
      },
      "The OPENBLAS_CORETYPE this CPU could run when OpenBLAS fell back to its SSE3 kernels (None otherwise). "
      "The drape program re-executes itself with it; a Python process gets it only when the variable is set "
      "before Python starts.");
  m.def(
      "plugin_search_path",
      []() {
        std::vector<std::string> out;
        for (const auto& p : Registry::search_path()) out.push_back(p.string());
        return out;
      },
      "Where plugins are looked for: $DRAPE_PLUGIN_PATH, then the plugins shipped next to the framework library.");
  m.def(
      "find_file", [](const std::string& name) { return find_input_file(name).string(); }, py::arg("name"),
      "A shipped file by its name in the source tree ('graphs/scenes/tshirt.yaml', 'models/tshirt-coarse.h5'): the "
      "name itself when it exists from the current folder, else the first of data_dirs() that holds it "
      "(ConfigError naming where it looked). Scene, Model.load and Dataset look paths up so.");
  m.def(
      "data_dirs",
      []() {
        std::vector<std::string> out;
        for (const auto& p : shipped_data_dirs()) out.push_back(p.string());
        return out;
      },
      "Where shipped files are looked for: $DRAPE_DATA_DIR, the installed share/drape (inside the package when "
      "pip-installed), the source tree of a build.");
}

}  // namespace drape::python
