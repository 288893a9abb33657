// Trained models: drape.Model.load(path).predict(body_vertices) (batched),
// optimize(scene, body), and what the PyTorch bridge needs -- the weights as
// writable arrays over drape's own memory, and reverse mode from a gradient of
// the predicted garment to the weights.
#include "common.hpp"

#include <drape/io/output_lock.hpp>
#include <drape/io/shipped_files.hpp>
#include <drape/io/write_failure.hpp>
#include <drape/geometry/body_units.hpp>
#include <drape/io/checkpoint.hpp>
#include <drape/errors.hpp>
#include <drape/graph.hpp>
#include <drape/training/model.hpp>
#include <drape/training/model_domain.hpp>
#include <drape/training/physics_optimization.hpp>
#include <drape/services/graded_scene.hpp>
#include <drape/services/model_body.hpp>
#include <drape/scene/scene_pose.hpp>
#include <drape/bodies/pose.hpp>

#include <chrono>
#include <filesystem>
#include <mutex>

namespace drape::python {
namespace {

namespace fs = std::filesystem;

// A notice of the shared preparation says what to change as the command
// line's flag; here, as predict's argument (an outside check's Python user
// was told "--garment-size names another").
std::string in_python_words(std::string text) {
  const std::string flag = "--garment-size", argument = "garment_size=";
  for (std::size_t at = text.find(flag); at != std::string::npos; at = text.find(flag, at + argument.size()))
    text.replace(at, flag.size(), argument);
  return text;
}

class PyModel {
 public:
  // The file's training domain is read here, with the weights: a domain read
  // later (at save) was another model's when the file had been overwritten
  // since, and none when it had been deleted (an outside check).
  explicit PyModel(Model model) : model_(std::make_unique<Model>(std::move(model))) {
    std::error_code ec;
    if (!model_->file().empty() && fs::is_regular_file(model_->file(), ec)) domain_at_load_ = read_domain(model_->file());
  }

  Model& model() { return *model_; }
  std::mutex& mutex() { return mutex_; }

  // The batch a graph takes for these bodies: body, and body_params / garment_size when the graph has those inputs.
  SampleBatch batch(const py::handle& body, const py::handle& body_params, const py::handle& garment_size, bool* batched) {
    SampleBatch b;
    b.body = vertices_batch_arg(body, "body_vertices", model_->assets().body.num_vertices(), batched);
    std::call_once(body_edges_once_, [this] { body_edges_ = model_body_edges(*model_); });
    for (int i = 0; i < b.body.batch(); ++i) {
      const std::string name = "body_vertices" + (batched && *batched ? "[" + std::to_string(i) + "]" : std::string());
      const Eigen::MatrixX3d vertices = b.body.mat(i).cast<double>();
      check_body_units(vertices, name);
      require_model_body_vertices(vertices, *model_, name, &body_edges_);
    }
    const int n = b.body.batch();
    if (model_->needs_body_params()) {
      const int p = model_->graph().input_shape("body_params").cols;
      const std::string expected = "a float array of shape [" + std::to_string(p) + "] or [" + std::to_string(n) + ", " +
                                   std::to_string(p) + "] (this model's graph takes the body parameters: Model.body_params())";
      if (body_params.is_none()) throw ConfigError("body_params: expected " + expected + ", got None");
      py::array a = py::array::ensure(body_params);
      if (!a || a.dtype().kind() != 'f' || a.shape(a.ndim() - 1) != p || a.ndim() > 2 || (a.ndim() == 2 && a.shape(0) != n))
        throw ConfigError("body_params: expected " + expected + (a ? ", got " + describe(a) : std::string()));
      auto f = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(a);
      b.body_params = Tensor(n, 1, p);
      for (int i = 0; i < n; ++i) std::copy(f.data() + (a.ndim() == 2 ? i * p : 0), f.data() + (a.ndim() == 2 ? i * p : 0) + p, &b.body_params(i, 0, 0));
    }
    if (!model_->needs_body_params() && !body_params.is_none())
      throw ConfigError("body_params: this model's graph takes no body parameters (it reads the body's vertices); "
                            "leave body_params out");
    if (model_->needs_input("garment_size")) {
      if (garment_size.is_none())
        throw ConfigError("garment_size: this model was trained on several garment sizes, give one of " + garment_size_choices());
      b.garment_size = Tensor(n, 1, 1, garment_size_flag(garment_size.cast<std::string>()));
    } else if (model_->needs_input("garment_grade")) {
      // A size name of the model's chart, "auto"/None (chosen per body by
      // BodyPreparation::prepare) or a grade as a number.
      std::optional<std::string> size;
      std::optional<double> grade;
      if (py::isinstance<py::str>(garment_size)) size = garment_size.cast<std::string>();
      else if (const std::optional<double> number = real_number(garment_size)) grade = number;
      else if (!garment_size.is_none())
        throw ConfigError("garment_size: a size name, \"auto\" or a grade (a number), got " +
                              py::repr(garment_size).cast<std::string>());
      try {
        if (const auto g = requested_garment_grade(*model_, size, grade)) b.garment_grade = Tensor(n, 1, 1, static_cast<float>(*g));
      } catch (const ConfigError& e) {
        throw ConfigError(std::string("garment_size: ") + e.what());
      }
    } else if (!garment_size.is_none()) {
      throw ConfigError("garment_size: this model was trained on one garment size and takes none; leave garment_size out");
    }
    return b;
  }

  Tensor predict(const SampleBatch& b) {
    py::gil_scoped_release release;
    std::lock_guard lock(mutex_);
    Tensor out = model_->predict(b);
    forward_id_ = ++forwards_;
    return out;
  }
  std::uint64_t last_forward() const { return forward_id_; }

  // What makes bodies ready for this model (services/model_body.hpp), built
  // once: the file's training domain (none for an untrained model or a file
  // written before domains were recorded) and the garment's loop.
  const BodyPreparation& preparation() {
    std::lock_guard lock(mutex_);
    if (!preparation_) preparation_.emplace(*model_, domain_at_load_);
    return *preparation_;
  }
  const std::optional<ModelDomain>& domain() { return preparation().domain(); }
  const std::optional<ModelDomain>& domain_at_load() const { return domain_at_load_; }

  // As drape predict does: each body standing away from where the training
  // bodies stood is moved there, the domain is checked (strict: ValueError
  // outside it) and a garment too small around is noted, each notice a Python
  // warning; returns per sample the move that takes its garment back (BodyMove::back).
  PreparedBodies prepare(SampleBatch& b, bool strict, bool check = true, bool pose_given = false) {
    if (strict && !check) throw ConfigError("strict=True needs check=True: the domain is checked by measuring the body");
    const BodyPreparation& preparation = this->preparation();
    PreparedBodies prepared = [&] {
      py::gil_scoped_release release;
      return preparation.prepare(b, strict, "strict=True", check, true, pose_given);
    }();
    for (const Notice& n : prepared.notices) warn_python(in_python_words(n.text));
    return prepared;
  }
  // Then the pose (BodyPreparation::pose): warnings for angles outside the training poses (strict: ValueError).
  void pose(SampleBatch& b, const std::optional<Pose>& pose, bool strict, const PreparedBodies& prepared, bool check = true,
            bool refuse_crossing = false) {
    const std::vector<Notice> notices =
        preparation().pose(b, pose ? *pose : Pose{}, strict, "strict=True", &prepared, check, refuse_crossing);
    for (const Notice& n : notices) warn_python(in_python_words(n.text));
  }

  // dL/dweights for a gradient of the garment, accumulated into the weights'
  // grad arrays (zeroed first). The graph keeps the state of its last forward;
  // when another forward ran since `forward_id` (a gradient check's
  // perturbations), this batch's forward is run again first.
  void backward(SampleBatch& b, const py::handle& grad, std::uint64_t forward_id) {
    const int ng = model_->assets().garment->mesh.num_vertices();
    bool batched = false;
    const Tensor g = vertices_batch_arg(grad, "grad_garment", ng, &batched);
    if (g.batch() != b.body.batch())
      throw ConfigError("grad_garment: expected " + std::to_string(b.body.batch()) + " samples like the forward, got " +
                            std::to_string(g.batch()));
    const BodyPreparation& preparation = this->preparation();  // before the lock, which it takes
    py::gil_scoped_release release;
    std::lock_guard lock(mutex_);
    if (forward_id != forward_id_) {
      preparation.choose_sizes(b);  // the forward's sizes: the same bodies, the same rule
      model_->predict(b);
      forward_id_ = ++forwards_;
    }
    model_->graph().zero_grad();
    model_->graph().backward_from_output(model_->output(), g);
  }

 private:
  std::unique_ptr<Model> model_;
  std::mutex mutex_;
  std::uint64_t forwards_ = 0, forward_id_ = 0;
  std::optional<BodyPreparation> preparation_;
  std::optional<ModelDomain> domain_at_load_;  // the file's, read with the weights (none: untrained, or not recorded)
  // The mean body's edges for the vertex-order check, made at the first body.
  std::once_flag body_edges_once_;
  ModelBodyEdges body_edges_;
};

Model::ParamOverrides overrides_of(const py::dict& d) {
  Model::ParamOverrides out;
  for (const auto& [node, params] : d) {
    if (!py::isinstance<py::str>(node) || !py::isinstance<py::dict>(params))
      throw ConfigError("overrides: expected {node: {param: value}}, e.g. {'post': {'enabled': False}}; got " +
                        py::repr(node).cast<std::string>() + ": " + py::repr(params).cast<std::string>());
    for (const auto& [name, value] : params.cast<py::dict>())
      out[node.cast<std::string>()][py::str(name).cast<std::string>()] = py::str(value).cast<std::string>();
  }
  return out;
}

fs::path cache_dir_of(const std::optional<std::string>& dir) { return dir ? fs::path(*dir) : default_cache_dir(); }

py::dict result_dict(PhysicsOptimizationResult&& r) {
  auto terms = [](const std::vector<EnergyTerm>& t) {
    std::vector<std::pair<std::string, double>> v;
    for (const auto& e : t) v.emplace_back(e.name, e.value);
    return energy_dict(v);
  };
  py::dict d;
  d["before"] = to_numpy(std::move(r.before));
  d["after"] = to_numpy(std::move(r.after));
  d["energies_before"] = terms(r.energies_before);
  d["energies_after"] = terms(r.energies_after);
  d["potential_before"] = r.potential_before;
  d["potential_after"] = r.potential_after;
  d["penetration_before"] = r.penetration_before;
  d["penetration_after"] = r.penetration_after;
  d["history"] = to_numpy(std::move(r.history));
  d["best_iteration"] = r.best_iteration;
  d["seconds"] = r.seconds;
  d["start_shrink"] = r.start_shrink;
  d["refused_steps"] = r.refused_steps;
  d["grown_iteration"] = r.grown_iteration;
  d["separated"] = r.separated;
  d["unseparated"] = r.unseparated;
  d["stopped"] = r.stopped;
  return d;
}

py::array weight_view(py::object self, Tensor& t) {
  // Writable: an optimiser (the PyTorch bridge's) steps drape's weights in place.
  return py::array_t<float>({static_cast<py::ssize_t>(t.rows()), static_cast<py::ssize_t>(t.cols())}, t.data(), self);
}

}  // namespace

void register_model(py::module_& m) {
  py::class_<PyModel>(m, "Model", "A trained model (drape train's output), or a graph with fresh weights.")
      .def_static(
          "load",
          [](const std::optional<std::string>& path, const py::dict& overrides, const std::optional<std::string>& cache_dir) {
            fs::path file = path ? find_input_file(*path) : default_model_path();  // models/... from anywhere
            if (file.empty())
              throw ConfigError(std::string("no model given and the shipped model (models/") + kDefaultModelFile + ") was not found: give a file from drape train, or set DRAPE_MODEL");
            // Read from the Python objects before the lock is let go (py::str
            // without it crashed every load with overrides).
            const Model::ParamOverrides set = overrides_of(overrides);
            py::gil_scoped_release release;
            return std::make_unique<PyModel>(Model::load(registry(), file, set, cache_dir_of(cache_dir)));
          },
          py::arg("path") = py::none(), py::arg("overrides") = py::dict(), py::arg("cache_dir") = py::none(),
          "Reads a model file (default: the shipped models/tshirt-coarse-human.h5, the coarse T-shirt on the human rig; models/tshirt-coarse.h5 is the mannequin's). overrides: {node: {param: value}} for knobs "
          "that leave the weights' shapes alone.")
      .def_static(
          "untrained",
          [](const std::string& graph, const py::dict& garment_params, int eigen_k, std::uint64_t seed,
             const std::optional<std::string>& cache_dir) {
            // A one-line string is a file's name, looked up as Scene and
            // Model.load look theirs up (shipped graphs from any folder; a
            // name found nowhere is "no such file", not YAML text that is no
            // map); YAML text has a newline, or a brace on its one line.
            const bool is_text = graph.find('\n') != std::string::npos || graph.find('{') != std::string::npos;
            const GraphSpec spec = is_text ? parse_graph_text(graph, "<graph text>") : parse_graph_file(find_input_file(graph));
            AssetsSpec assets;
            for (const auto& [k, v] : garment_params) assets.garment_params[k.cast<std::string>()] = py::str(v).cast<std::string>();
            assets.eigen_k = eigen_k;
            py::gil_scoped_release release;
            return std::make_unique<PyModel>(Model::untrained(registry(), spec, assets, seed, cache_dir_of(cache_dir)));
          },
          py::arg("graph"), py::arg("garment_params") = py::dict(), py::arg("eigen_k") = 1000, py::arg("seed") = 0,
          py::arg("cache_dir") = py::none(),
          "A graph (a YAML file, a shipped one by its name such as 'graphs/examples/mlp_baseline.yaml', or the "
          "YAML text itself, several lines or one in braces) with freshly initialised weights on the template's "
          "assets, e.g. garment_params={'resolution': 'coarse'}.")
      .def_property_readonly("file", [](PyModel& p) { return p.model().file().string(); })
      .def_property_readonly("assets", [](PyModel& p) { return wrap_assets(p.model().shared_assets()); })
      .def_property_readonly("body_vertex_count", [](PyModel& p) { return p.model().assets().body.num_vertices(); })
      .def_property_readonly(
          "body_spec",
          [](PyModel& p) {
            const AssetsSpec& spec = p.model().assets_spec();
            return py::dict(py::arg("model") = spec.body_model, py::arg("params") = spec.body_params);
          },
          "the model's body as a scene's `body:` names it, {'model': ..., 'params': {...}} (the human rig's "
          "{'rig': 'human'}): a drape.Scene dict with it drapes the bodies this model takes")
      .def_property_readonly("garment_vertex_count", [](PyModel& p) { return p.model().assets().garment->mesh.num_vertices(); })
      .def_property_readonly("inputs", [](PyModel& p) { return p.model().graph().input_names(); })
      .def_property_readonly("needs_body_params", [](PyModel& p) { return p.model().needs_body_params(); })
      .def_property_readonly("needs_garment_size", [](PyModel& p) { return p.model().needs_input("garment_size"); })
      .def_property_readonly("takes_pose", [](PyModel& p) { return model_takes_pose(p.model()); },
                             "True for a model of posed drapes (predict takes pose=...)")
      .def_property_readonly("pose_angles", [](PyModel& p) { return p.model().assets().pose_angles; },
                             "the body model's joint angle names, in the order of the graph input pose")
      .def_property_readonly("assets_changed", [](PyModel& p) { return p.model().assets_changed(); })
      .def_property_readonly("graph", [](PyModel& p) { return p.model().checkpoint().graph; }, "the resolved graph, YAML")
      .def(
          "body",
          [](PyModel& p, const py::handle& bmi, const py::handle& height, const py::handle& sex, const py::kwargs& girths) {
            const BodyRequest r = body_request(bmi, height, sex, girths, p.model().assets_spec().body_model);
            SampleBatch b;
            {
              py::gil_scoped_release release;
              b = p.model().body_for(r);
            }
            return to_numpy(std::move(b.body), true);
          },
          py::arg("bmi") = 24.0, py::arg("height") = 1.75, py::arg("sex") = 1.0,
          "float32 [Nb, 3]: a body of the model's own body plugin; keywords are proportions held (girths, as drape.body)")
      .def(
          "body_params",
          [](PyModel& p, const py::handle& bmi, const py::handle& height, const py::handle& sex, const py::kwargs& girths) {
            const BodyRequest r = body_request(bmi, height, sex, girths, p.model().assets_spec().body_model);
            SampleBatch b;
            {
              py::gil_scoped_release release;
              b = p.model().body_for(r);
            }
            Tensor params = std::move(b.body_params);
            const int n = params.cols();
            auto a = to_numpy(std::move(params), true);
            return a.reshape({n});
          },
          py::arg("bmi") = 24.0, py::arg("height") = 1.75, py::arg("sex") = 1.0,
          "float32 [P]: the body plugin's shape parameters of that body (for graphs that take body_params)")
      .def(
          "predict",
          [](PyModel& p, const py::handle& body, const py::handle& body_params, const py::handle& garment_size, bool strict,
             bool check, const py::handle& pose) {
            bool batched = false;
            const std::optional<Pose> posed = pose_arg(p.model().body_model(), p.model().assets_spec().body_model, pose);
            SampleBatch b = p.batch(body, body_params, garment_size, &batched);
            const PreparedBodies prepared = p.prepare(b, strict, check, posed.has_value());
            p.pose(b, posed, strict, prepared, check);
            const std::vector<BodyMove>& back = prepared.moved_by;
            Tensor out = p.predict(b);
            // Moved back as drape predict writes it (in double), then float32 like every prediction.
            for (int i = 0; i < out.batch(); ++i)
              if (const BodyMove& move = back[static_cast<std::size_t>(i)]; !move.is_identity())
                out.mat(i) = move.back(out.mat(i).cast<double>()).cast<float>();
            return to_numpy(std::move(out), !batched);
          },
          py::arg("body_vertices"), py::arg("body_params") = py::none(), py::arg("garment_size") = py::none(),
          py::arg("strict") = false, py::arg("check") = true, py::arg("pose") = py::none(),
          "float32 garments [Ng, 3] for a body [Nb, 3], or [n, Ng, 3] for a batch [n, Nb, 3], as drape predict makes "
          "them (pose: for a model of posed drapes, joint angles in degrees, {'shoulder_abduction': 60} or "
          "'shoulder_abduction=60,...'; the body given is unposed and posed with it, docs/poses.md): a body standing away from where the training bodies stood is draped there and its garment moved back, "
          "a body outside the training domain and a garment too small around for it are warned about (each a Python "
          "warning; strict=True: a body outside the domain raises ValueError), and so is a pose in which the body "
          "passes through itself. check=False skips those measurements of the body (about 5 ms each call for the "
          "parametric body, several times the coarse network's forward; the pose's test about 15 ms), keeping the "
          "placement. The GIL is released.")
      .def(
          "domain_check",
          [](PyModel& p, const py::handle& body) {
            bool batched = false;
            const Tensor t = vertices_batch_arg(body, "body_vertices", p.model().assets().body.num_vertices(), &batched);
            if (t.batch() != 1) throw ConfigError("body_vertices: domain_check takes one body [Nb, 3]");
            const std::optional<ModelDomain>& d = p.domain();
            if (!d) return std::vector<std::string>{"the model records no training domain (drape model domain adds it)"};
            return domain_violations(*d, t.mat(0).cast<double>(), p.model().assets().body.faces, nullptr);
          },
          py::arg("body_vertices"),
          "[str]: how a body [Nb, 3] lies outside the model's training domain, one line per measure (as drape predict "
          "warns); empty when inside")
      .def(
          "optimize",
          [](PyModel& p, const PyScene& scene, const py::handle& body, const py::handle& body_params, int iterations,
             double learning_rate, const py::handle& pose, const py::handle& garment_size) {
            bool batched = false;
            std::optional<Pose> posed = pose_arg(p.model().body_model(), p.model().assets_spec().body_model, pose);
            SampleBatch b = p.batch(body, body_params, garment_size, &batched);
            if (b.size() != 1) throw ConfigError("body_vertices: optimize takes one body [Nb, 3], got a batch of " + std::to_string(b.size()));
            if (iterations < 0) throw ConfigError("iterations: expected >= 0");
            // Optimised where the training bodies stood (as predict), the drapes moved back with the body.
            const PreparedBodies prepared = p.prepare(b, false, true, posed.has_value());
            // pose=None: the scene's `body: pose:`, as drape optimize takes it (it optimised the unposed
            // body and measured p = 0 against it); a body given posed keeps its own.
            bool scene_posed = false;
            if (!posed && !prepared.given_posed(0))
              if (Pose from_scene = scene_pose(scene.simulations->design().scene(), p.model().body_model()); !from_scene.empty())
                posed = std::move(from_scene), scene_posed = true;
            try {
              p.pose(b, posed, false, prepared, true, true);  // (an optimisation refuses a pose through the body, as optimize does)
            } catch (const ConfigError& e) {
              if (!scene_posed) throw;
              throw ConfigError("the scene's body: pose: (" + format_pose(*posed) + ", pose= replaces it): " + e.what());
            }
            const BodyMove back = prepared.moved_by.front();
            // A model of several sizes: against the garment the scene dresses this body in, fed that grade.
            // Another garment than the rule chose, said as drape optimize says it (an outside check's Python
            // user was told "size large" of a drape optimised in regular).
            std::string regraded;
            const Simulation& simulation = GradedScene(registry(), *scene.simulations)
                                               .for_model(p.model(), b, !garment_size.is_none(), "optimize", &regraded);
            if (!regraded.empty()) warn_python(regraded);
            PhysicsOptimizationOptions o;
            o.iterations = iterations;
            o.learning_rate = learning_rate;
            const bool interruptible = in_python_main_thread();
            if (interruptible) o.on_iteration = [](int, double) { check_python_signals(); };
            PhysicsOptimizationResult r;
            try {
              py::gil_scoped_release release;
              std::lock_guard lock(p.mutex());
              // The weights as they were (taken under the model's lock), put back when
              // Ctrl-C stops the optimisation: the model kept an iteration's half-made weights.
              std::vector<Tensor> before;
              if (interruptible)
                for (const auto& weight : p.model().graph().weights()) before.push_back(weight.second->value);
              try {
                r = optimize_drape(p.model(), simulation, b, o);
              } catch (const PythonSignal&) {
                std::size_t k = 0;
                for (const auto& weight : p.model().graph().weights()) weight.second->value = before[k++];
                throw;
              }
            } catch (const PythonSignal&) {
              throw py::error_already_set();  // KeyboardInterrupt, as PyErr_CheckSignals set it
            }
            r.before = back.back(r.before);
            r.after = back.back(r.after);
            return result_dict(std::move(r));
          },
          py::arg("scene"), py::arg("body_vertices"), py::arg("body_params") = py::none(), py::arg("iterations") = 100,
          py::arg("learning_rate") = 1e-4, py::arg("pose") = py::none(), py::arg("garment_size") = py::none(),
          "The seed's physics-enforced optimisation (as drape optimize): fine-tunes this model's weights in place so that "
          "its drape of one body minimises the scene's potential. pose=None poses the body as the scene's body: pose: "
          "does (a body given posed keeps its own pose). Returns before/after garments, energies, p and the "
          "history (history[0]: before's potential). 'before' is the prediction as predict gives it; with a push-out "
          "the drape optimised is the network's own plus the push-out's correction of the prediction, held fixed (the "
          "push-out is not learnt; docs/optimization.md). The GIL is released; Ctrl-C stops it (KeyboardInterrupt) with the "
          "model's weights as they were before the call.")
      .def(
          "save",
          [](PyModel& p, const std::string& path, const std::map<std::string, std::string>& meta) {
            // The model as drape train writes one (docs/formats.md): what Model::load and the drape program read back.
            Model& m = p.model();
            Checkpoint c = m.checkpoint();
            c.optimizer.reset();  // an optimiser state belongs to the training that wrote it
            for (const auto& [k, v] : meta) c.meta[k] = v;
            c.meta["kind"] = "drape model";
            c.meta["assets"] = m.assets_spec().yaml();
            c.meta["assets_hash"] = m.assets().hash;
            c.meta["output"] = m.output();
            // The training domain of the file it was loaded from, kept as
            // drape model set keeps it (it was dropped: model info then said
            // "written before drape recorded it", predict warned of no body
            // outside it and --strict refused every body; an outside check).
            // (Read when the model was loaded; an untrained model has none.)
            py::gil_scoped_release release;
            std::lock_guard lock(p.mutex());
            // As drape model set writes one: the output's lock (a drape
            // train running on it wrote over this save at its next epoch),
            // and over a model only (a dataset named here was replaced).
            const OutputLock output(path, "Model.save");
            refuse_replacing_other_than_a_model(path, "save:");
            save_model_file(path, m.graph().weights(), c, p.domain_at_load());
          },
          py::arg("path"), py::arg("meta") = std::map<std::string, std::string>{},
          "Writes the model with its current weights (after optimize or a PyTorch loop) as a model file, atomically, over nothing but a model and not while another job writes the path (ConfigError); "
          "meta: extra string attributes for /meta.")
      .def(
          "weights",
          [](py::object self) {
            py::dict d;
            for (auto& [name, w] : self.cast<PyModel&>().model().graph().weights()) d[py::str(name)] = weight_view(self, w->value);
            return d;
          },
          "{node/weight: float32 [rows, cols]}: writable views of the model's own weights (no copies)")
      .def(
          "grads",
          [](py::object self) {
            py::dict d;
            for (auto& [name, w] : self.cast<PyModel&>().model().graph().weights()) d[py::str(name)] = weight_view(self, w->grad);
            return d;
          },
          "{node/weight: float32 [rows, cols]}: views of the gradients the last _backward accumulated")
      .def(
          "_forward",
          [](PyModel& p, const py::handle& body, const py::handle& body_params, const py::handle& garment_size) {
            bool batched = false;
            SampleBatch b = p.batch(body, body_params, garment_size, &batched);
            p.preparation().choose_sizes(b);  // a model of sizes: the tailor's rule, as predict (no notes here)
            py::array out = to_numpy(p.predict(b), !batched);
            return py::make_tuple(out, p.last_forward());
          },
          py::arg("body_vertices"), py::arg("body_params") = py::none(), py::arg("garment_size") = py::none())
      .def_property_readonly("_last_forward", &PyModel::last_forward, "the id of the forward whose state the graph holds")
      .def(
          "_backward",
          [](PyModel& p, const py::handle& grad, std::uint64_t forward_id, const py::handle& body, const py::handle& body_params,
             const py::handle& garment_size) {
            bool batched = false;
            SampleBatch b = p.batch(body, body_params, garment_size, &batched);
            p.backward(b, grad, forward_id);
          },
          py::arg("grad_garment"), py::arg("forward_id"), py::arg("body_vertices"), py::arg("body_params") = py::none(),
          py::arg("garment_size") = py::none())
      .def(
          "_predict_timed",
          [](PyModel& p, const py::handle& body, int repeats) {
            // The C++ side of the overhead benchmark: Model::predict timed in C++, no Python in the loop.
            bool batched = false;
            SampleBatch b = p.batch(body, py::none(), py::none(), &batched);
            p.preparation().choose_sizes(b);
            std::vector<double> seconds;
            py::gil_scoped_release release;
            std::lock_guard lock(p.mutex());
            for (int i = 0; i < repeats; ++i) {
              const auto t0 = std::chrono::steady_clock::now();
              const Tensor out = p.model().predict(b);
              seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
            }
            return seconds;
          },
          py::arg("body_vertices"), py::arg("repeats"));
}

}  // namespace drape::python
