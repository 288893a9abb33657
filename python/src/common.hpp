#pragma once
// What every area of the Python module shares: the plugin registry, argument
// checks that name the argument and the shape it wants, and NumPy arrays that
// own drape's memory instead of copying it.
#include <drape/assets/assets.hpp>
#include <drape/bodies/body.hpp>
#include <drape/scene/garment_size.hpp>
#include <drape/registry.hpp>
#include <drape/scene/simulation.hpp>
#include <drape/tensor.hpp>

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace drape::python {

namespace py = pybind11;

// The process-wide registry: plugins next to the framework library and in
// $DRAPE_PLUGIN_PATH, plus any folder given to drape.load_plugins().
Registry& registry();

// Python's ValueError with a message naming the argument, e.g.
// "body_vertices: expected a float array of shape [N, 3] (N = 1665), got int64 [3, 3]".
[[noreturn]] void bad_argument(const std::string& name, const std::string& expected, const py::array& got);
std::string describe(const py::array& a);  // "float32 [2, 1665, 3]"

// A float array of vertices: [rows, 3] (rows < 0: any). Returned as double,
// copied only when the dtype or layout differs. Throws ValueError naming `name`.
Eigen::MatrixX3d vertices_arg(const py::handle& value, const std::string& name, int rows = -1);
// The same, and ConfigError (a ValueError) naming the argument and the row when a coordinate is not finite.
Eigen::MatrixX3d finite_vertices_arg(const py::handle& value, const std::string& name, int rows = -1);
// Float vertices batched as a Tensor [n, rows, 3] from [rows, 3] (n = 1) or
// [n, rows, 3]; `batched` says which was given.
Tensor vertices_batch_arg(const py::handle& value, const std::string& name, int rows, bool* batched);

// A body request from Python's arguments: keywords are proportions (girths)
// held while the BMI is reached; ValueError for one that is not a number.
// A real number as Python counts one (numbers.Real: float, int, NumPy's
// float32, int64, ...), not a bool (True is a mistake, not 1.0); none
// otherwise (a string, a complex, an array).
std::optional<double> real_number(const py::handle& value);
// bmi, height and sex likewise: real numbers, ConfigError naming the one that is not (a bool, a string).
double number_arg(const py::handle& value, const std::string& name);
BodyRequest body_request(const py::handle& bmi, const py::handle& height, const py::handle& sex, const py::dict& girths, const std::string& model_name);

// Ctrl-C in a long call that runs without the GIL (Scene.simulate,
// Model.optimize): the job's own callbacks (a solver step, an iteration)
// take the GIL and ask Python whether a signal is pending; one is, and
// PythonSignal unwinds the job. The binding catches it where it holds the
// GIL again and raises Python's own exception (KeyboardInterrupt), which
// PyErr_CheckSignals left set. (A simulation ran on to its end, 87 s, and
// its result was thrown away: an outside check.)
struct PythonSignal {};
void check_python_signals();  // throws PythonSignal; call without the GIL
// Whether a signal can reach this call: Python runs its handlers in the
// main thread only (PyErr_CheckSignals does nothing in another), so a call
// from a worker thread installs no check and takes no GIL at each step.
// Call with the GIL.
bool in_python_main_thread();

// Arrays that keep drape's buffers alive through a capsule: no copy.
py::array_t<float> to_numpy(Tensor&& t, bool drop_batch);
py::array_t<double> to_numpy(Eigen::MatrixX3d&& m);  // [N, 3], column-major strides (Fortran order)
py::array_t<double> to_numpy(Eigen::VectorXd&& v);
py::array_t<int> to_numpy(Eigen::MatrixX3i&& m);
template <class T>
py::array_t<T> to_numpy(std::vector<T>&& v) {
  auto* owned = new std::vector<T>(std::move(v));
  py::capsule free_it(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>({static_cast<py::ssize_t>(owned->size())}, owned->data(), free_it);
}

// A scene made runnable (scene.cpp); Model.optimize takes one. With size:
// auto, `simulations` holds every size and `simulation` is the design size's.
struct PyScene {
  std::shared_ptr<const SceneSimulations> simulations;
  std::shared_ptr<const Simulation> simulation;  // aliases simulations->design()
};

py::object wrap_assets(std::shared_ptr<const Assets> assets);  // drape._Assets (assets.cpp)

// A Python warning of category drape.DrapeWarning (a UserWarning): what
// drape::warn and the services' notices become in Python.
void warn_python(const std::string& text);

// dict {name: value} of scene energies.
py::dict energy_dict(const std::vector<std::pair<std::string, double>>& terms);

// Registration of each area, called by the module's init (module.cpp).
void register_errors(py::module_& m);
void register_bodies(py::module_& m);
void register_assets(py::module_& m);
void register_model(py::module_& m);
void register_scene(py::module_& m);
void register_dataset(py::module_& m);

}  // namespace drape::python

namespace drape::python {

// A read-only NumPy view of memory owned by `owner` (kept alive by the array).
template <class T>
py::array view(const T* data, std::vector<py::ssize_t> shape, std::vector<py::ssize_t> strides, py::handle owner) {
  py::array a(py::dtype::of<T>(), std::move(shape), std::move(strides), data, owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}
// Views of column-major Eigen matrices as [rows, cols] arrays.
template <class Derived>
py::array view(const Eigen::PlainObjectBase<Derived>& m, py::handle owner) {
  using T = typename Derived::Scalar;
  const auto r = static_cast<py::ssize_t>(m.rows()), c = static_cast<py::ssize_t>(m.cols());
  const auto s = static_cast<py::ssize_t>(sizeof(T));
  if constexpr (Derived::IsVectorAtCompileTime) return view<T>(m.data(), {r * c}, {s}, owner);
  else if constexpr (Derived::IsRowMajor) return view<T>(m.data(), {r, c}, {c * s, s}, owner);
  else return view<T>(m.data(), {r, c}, {s, r * s}, owner);
}
// A sparse matrix as COO arrays (rows, cols, values, shape); drape/__init__.py makes it SciPy's when SciPy is there.
template <class Sparse>
py::tuple coo(const Sparse& s) {
  std::vector<int> rows, cols;
  std::vector<typename Sparse::Scalar> values;
  rows.reserve(s.nonZeros());
  cols.reserve(s.nonZeros());
  values.reserve(s.nonZeros());
  for (int k = 0; k < s.outerSize(); ++k)
    for (typename Sparse::InnerIterator it(s, k); it; ++it) {
      rows.push_back(static_cast<int>(it.row()));
      cols.push_back(static_cast<int>(it.col()));
      values.push_back(it.value());
    }
  return py::make_tuple(to_numpy(std::move(rows)), to_numpy(std::move(cols)), to_numpy(std::move(values)),
                        py::make_tuple(s.rows(), s.cols()));
}

// A pose argument (None, "name=degrees,...", {name: degrees}) checked
// against `model`'s pose space; None gives nullopt. ConfigError (ValueError)
// naming the angle, or saying the model has no skeleton.
std::optional<Pose> pose_arg(const BodyModel& model, const std::string& model_name, const py::handle& pose);

}  // namespace drape::python
