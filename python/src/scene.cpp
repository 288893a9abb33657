// Scenes: the cloth simulation (drape.simulate) and each energy of a scene on
// its own -- value, gradient and Hessian -- which is what the PyTorch bridge
// turns into an autograd Function. Physics in double, as in the simulator.
#include "common.hpp"

#include <drape/scene/rode_up.hpp>
#include <drape/io/shipped_files.hpp>
#include <drape/bodies/pose.hpp>
#include <drape/bodies/posed_body.hpp>
#include <drape/errors.hpp>
#include <drape/geometry/closest_point.hpp>
#include <drape/scene/scene.hpp>
#include <drape/services/scene_body.hpp>
#include <drape/scene/simulation.hpp>

#include <memory>
#include <optional>
#include <sstream>

namespace drape::python {
namespace {

// A scene's energies bound to the garment and one body, as the simulator binds them.
class PyEnergies {
 public:
  PyEnergies(std::shared_ptr<const Simulation> sim, const Eigen::MatrixX3d& body) : sim_(std::move(sim)) {
    if (sim_->needs_body()) body_ = std::make_unique<geometry::BodySurface>(body, sim_->body_model().faces());
    energies_ = sim_->make_energies(body_.get());
  }

  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& e : energies_) out.push_back(e.name);
    return out;
  }
  int garment_vertices() const { return sim_->garment().mesh.num_vertices(); }

  const Energy& get(const std::string& name) const {
    for (const auto& e : energies_)
      if (e.name == name) return *e.energy;
    throw py::key_error("the scene has no effect '" + name + "'" + did_you_mean(name, names()));
  }
  Eigen::MatrixX3d state(const py::handle& x) const { return vertices_arg(x, "garment_vertices", garment_vertices()); }

  double value(const std::string& name, const py::handle& x_arg) const {
    const Energy& e = get(name);
    const Eigen::MatrixX3d x = state(x_arg);
    py::gil_scoped_release release;
    return e.value(x);
  }
  py::tuple value_and_gradient(const std::string& name, const py::handle& x_arg) const {
    const Energy& e = get(name);
    const Eigen::MatrixX3d x = state(x_arg);
    Eigen::MatrixX3d g = Eigen::MatrixX3d::Zero(x.rows(), 3);
    double v = 0;
    {
      py::gil_scoped_release release;
      v = e.add_gradient(x, g);
    }
    return py::make_tuple(v, to_numpy(std::move(g)));
  }
  // Triplets on the flattened index 3*vertex + axis; duplicates are summed by whoever assembles them.
  py::tuple hessian(const std::string& name, const py::handle& x_arg, bool project_psd) const {
    const Energy& e = get(name);
    const Eigen::MatrixX3d x = state(x_arg);
    Triplets t;
    {
      py::gil_scoped_release release;
      e.add_hessian(x, t, project_psd);
    }
    std::vector<int> rows(t.size()), cols(t.size());
    std::vector<double> values(t.size());
    for (std::size_t i = 0; i < t.size(); ++i) {
      rows[i] = t[i].row();
      cols[i] = t[i].col();
      values[i] = t[i].value();
    }
    const int n = 3 * garment_vertices();
    return py::make_tuple(to_numpy(std::move(rows)), to_numpy(std::move(cols)), to_numpy(std::move(values)), py::make_tuple(n, n));
  }
  double max_step(const std::string& name, const py::handle& x_arg, const py::handle& dx_arg) const {
    const Energy& e = get(name);
    // Finite only: a NaN position or step was "1.0", every step safe, from
    // the energies finite everywhere, where value() refuses it.
    const Eigen::MatrixX3d x = finite_vertices_arg(x_arg, "garment_vertices", garment_vertices()),
                          dx = finite_vertices_arg(dx_arg, "step", garment_vertices());
    py::gil_scoped_release release;
    return e.max_step(x, dx);
  }

 private:
  std::shared_ptr<const Simulation> sim_;
  std::unique_ptr<geometry::BodySurface> body_;
  std::vector<NamedEnergy> energies_;
};

PyScene make_scene(Scene scene) {
  py::gil_scoped_release release;
  auto simulations = std::make_shared<const SceneSimulations>(registry(), scene);
  std::shared_ptr<const Simulation> design(simulations, &simulations->design());
  return PyScene{std::move(simulations), std::move(design)};
}

// What drape simulate drapes (services/scene_body.hpp): a given body checked
// and placed where the body model's bodies stand, the size it wears with
// size: auto; the scene's own target body without one.
std::optional<Pose> scene_pose_arg(const PyScene& s, const py::handle& pose) {
  return drape::python::pose_arg(s.simulation->body_model(), s.simulation->scene().body_model, pose);
}

SceneBody scene_body_arg(const PyScene& s, const py::handle& body, const py::handle& pose_given) {
  const std::optional<Pose> pose = scene_pose_arg(s, pose_given);
  const Pose* posed = pose ? &*pose : nullptr;
  if (body.is_none()) return scene_body(*s.simulations, s.simulation->target_request(), s.simulation->scene().file, posed);
  const Eigen::MatrixX3d given = vertices_arg(body, "body_vertices", static_cast<int>(s.simulation->mean_body().rows()));
  py::gil_scoped_release release;
  return scene_body(*s.simulations, given, "body_vertices", posed);
}

Eigen::MatrixX3d body_or_target(const Simulation& sim, const py::handle& body) {
  if (body.is_none())  // the scene's own body, in the scene's pose
    return pose_vertices(sim.body_model(), sim.scene().body_model, sim.body_vertices(sim.target_shape()), sim.target_pose());
  return finite_vertices_arg(body, "body_vertices", static_cast<int>(sim.mean_body().rows()));
}

// The simulation whose energies act on `body`: with size: auto the size it wears.
std::shared_ptr<const Simulation> simulation_for(const PyScene& s, const Eigen::MatrixX3d& body) {
  if (!s.simulations->auto_size()) return s.simulation;
  return std::shared_ptr<const Simulation>(s.simulations, &s.simulations->for_body(body, "body_vertices"));
}

py::dict result_dict(SimulationResult&& r) {
  std::vector<std::pair<std::string, double>> terms;
  for (const auto& e : r.energies) terms.emplace_back(e.name, e.value);
  py::dict d;
  d["garment"] = to_numpy(std::move(r.garment));
  d["body"] = to_numpy(std::move(r.body));
  d["energies"] = energy_dict(terms);
  d["total_energy"] = r.total_energy;
  d["initial_energy"] = r.initial_energy;
  d["penetration"] = r.penetration;
  if (r.crossings) {
    py::dict c;
    c["garment_edges_through_body"] = r.crossings->garment_edges_through_body;
    c["body_edges_through_garment"] = r.crossings->body_edges_through_garment;
    d["crossings"] = c;
  } else {
    d["crossings"] = py::none();
  }
  d["self_crossings"] = r.self_crossings ? py::object(py::int_(*r.self_crossings)) : py::object(py::none());
  d["residual"] = r.residual;
  d["stationarity"] = r.stationarity;
  d["converged"] = r.converged;
  d["at_rest"] = r.at_rest;
  d["sliding"] = r.sliding();
  d["slip_ratio"] = r.slip_ratio;
  d["unsettled"] = r.unsettled;
  d["steps"] = r.steps;
  d["iterations"] = r.iterations;
  d["start_shrink"] = r.start_shrink;
  d["seconds"] = r.seconds;
  return d;
}

}  // namespace

void register_scene(py::module_& m) {
  py::class_<PyScene>(m, "_Scene")
      .def_static("from_file", [](const std::string& path) { return make_scene(load_scene(find_input_file(path))); }, py::arg("path"))
      .def_static("from_text", [](const std::string& text, const std::string& name) { return make_scene(parse_scene(text, name)); },
                  py::arg("text"), py::arg("name"))
      .def_property_readonly("file", [](const PyScene& s) { return s.simulation->scene().file; })
      .def_property_readonly("yaml", [](const PyScene& s) { return s.simulation->scene().yaml(); })
      .def_property_readonly("effects", [](const PyScene& s) {
        std::vector<std::string> out;
        for (const auto& e : s.simulation->scene().effects) out.push_back(e.name);
        return out;
      })
      .def_property_readonly("garment_vertices", [](py::object self) { return view(self.cast<PyScene&>().simulation->garment().mesh.vertices, self); },
                             "float64 [Ng, 3]: the garment dressed on its fit body (the start state; the mean body for the regular size)")
      .def_property_readonly("garment_faces", [](py::object self) { return view(self.cast<PyScene&>().simulation->garment().mesh.faces, self); })
      .def_property_readonly("mean_body", [](py::object self) { return view(self.cast<PyScene&>().simulation->mean_body(), self); })
      .def_property_readonly("fit_body", [](py::object self) { return view(self.cast<PyScene&>().simulation->fit_body(), self); },
                             "float64 [Nb, 3]: the body the garment is dressed on and every simulation starts from: the mean "
                             "body, or a larger size's body of its girth (docs/garments.md, \"Sizes\")")
      .def_property_readonly("body_faces", [](py::object self) { return view(self.cast<PyScene&>().simulation->body_model().faces(), self); })
      .def(
          "body",
          [](const PyScene& s, const py::handle& bmi, const py::handle& height, const py::handle& sex) {
            if (bmi.is_none() && height.is_none() && sex.is_none())
              return to_numpy(s.simulation->body_vertices(s.simulation->target_shape()));
            BodyRequest r;
            if (!bmi.is_none()) r.bmi = number_arg(bmi, "bmi");
            if (!height.is_none()) r.height = number_arg(height, "height");
            if (!sex.is_none()) r.sex = number_arg(sex, "sex");
            Eigen::MatrixX3d v;
            {
              py::gil_scoped_release release;
              v = s.simulation->body_vertices(s.simulation->shape_for(r));
            }
            return to_numpy(std::move(v));
          },
          py::arg("bmi") = py::none(), py::arg("height") = py::none(), py::arg("sex") = py::none(),
          "float64 [Nb, 3]: the scene's own target body, or one of this BMI, height and sex")
      .def(
          "simulate",
          [](const PyScene& s, const py::handle& body, const py::handle& start_garment, bool measure_penetration,
             const py::handle& start_body, const py::handle& pose) {
            const SceneBody target = scene_body_arg(s, body, pose);
            for (const std::string& note : target.notes) warn_python(note);
            for (const std::string& note : s.simulation->effect_notes()) warn_python(note);  // as the program's notes
            Eigen::MatrixX3d start, start_b;
            SimulationOptions o;
            o.measure_penetration = measure_penetration;
            if (!start_garment.is_none()) {
              start = finite_vertices_arg(start_garment, "start_garment", s.simulation->garment().mesh.num_vertices());
              o.start_garment = &start;
            }
            if (!start_body.is_none()) {
              start_b = finite_vertices_arg(start_body, "start_body", static_cast<int>(s.simulation->mean_body().rows()));
              o.start_body = &start_b;
            }
            if (in_python_main_thread()) {
              o.on_step = [](const SimulationStep&) { check_python_signals(); };
              o.on_partial_move = [](int, int, int, double) { check_python_signals(); };
            }
            SimulationResult r;
            try {
              py::gil_scoped_release release;
              r = drape_scene_body(target, o);
            } catch (const PythonSignal&) {
              throw py::error_already_set();  // KeyboardInterrupt, as PyErr_CheckSignals set it
            }
            // As drape simulate notes it: a garment too small round the body rode up into a band.
            if (const std::string note = garment_rode_up(target.simulation->garment().mesh.vertices, r.garment); !note.empty())
              warn_python(note);
            py::dict d = result_dict(std::move(r));
            d["size"] = target.size ? py::cast(target.size->summary()) : py::none();
            d["garment_size"] = target.size ? py::cast(target.size->size) : py::none();
            py::dict angles;
            for (const auto& [name, degrees] : target.pose.angles) angles[py::str(name)] = degrees;
            d["pose"] = angles;
            return d;
          },
          py::arg("body_vertices") = py::none(), py::arg("start_garment") = py::none(), py::arg("measure_penetration") = true,
          py::arg("start_body") = py::none(), py::arg("pose") = py::none())
      .def(
          "energies",
          [](const PyScene& s, const py::handle& body) {
            const Eigen::MatrixX3d b = body_or_target(*s.simulation, body);
            py::gil_scoped_release release;
            return std::make_unique<PyEnergies>(simulation_for(s, b), b);
          },
          py::arg("body_vertices") = py::none());

  py::class_<PyEnergies>(m, "_Energies")
      .def_property_readonly("names", &PyEnergies::names)
      .def_property_readonly("garment_vertex_count", &PyEnergies::garment_vertices)
      .def("value", &PyEnergies::value, py::arg("name"), py::arg("garment_vertices"))
      .def("value_and_gradient", &PyEnergies::value_and_gradient, py::arg("name"), py::arg("garment_vertices"))
      .def("hessian", &PyEnergies::hessian, py::arg("name"), py::arg("garment_vertices"), py::arg("project_psd") = false)
      .def("max_step", &PyEnergies::max_step, py::arg("name"), py::arg("garment_vertices"), py::arg("step"));
}

}  // namespace drape::python
