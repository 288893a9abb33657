// The shared helpers of common.hpp and the exception mapping: drape::ConfigError
// becomes drape.ConfigError (also a ValueError: the caller's input is at
// fault), any other drape::Error becomes drape.Error (a RuntimeError). Both
// carry the same one-line message the drape program prints.
#include "common.hpp"

#include <drape/warnings.hpp>

#include <drape/errors.hpp>
#include <drape/geometry/body_units.hpp>
#include <drape/bodies/pose.hpp>

#include <Python.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <vector>

namespace drape::python {

bool in_python_main_thread() {
  const py::module_ threading = py::module_::import("threading");
  return threading.attr("current_thread")().is(threading.attr("main_thread")());
}

void check_python_signals() {
  py::gil_scoped_acquire gil;
  if (PyErr_CheckSignals() != 0) throw PythonSignal{};
}


Registry& registry() { return Registry::load_default(); }

std::string describe(const py::array& a) {
  std::ostringstream s;
  s << py::str(a.dtype()).cast<std::string>() << " [";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s << (i ? ", " : "") << a.shape(i);
  s << "]";
  return s.str();
}

void bad_argument(const std::string& name, const std::string& expected, const py::array& got) {
  throw ConfigError(name + ": expected " + expected + ", got " + describe(got));
}

namespace {

py::array as_array(const py::handle& value, const std::string& name, const std::string& expected) {
  if (py::isinstance<py::array>(value)) return py::reinterpret_borrow<py::array>(value);
  // (NumPy makes an object array of None: it said "got object []".)
  if (value.is_none()) throw ConfigError(name + ": expected " + expected + ", got None");
  // Lists and objects exposing __array__ (a CPU torch tensor) become arrays; anything else is refused.
  py::array a = py::array::ensure(value);
  if (a) return a;
  std::string why;
  try {
    // (ensure clears NumPy's own reason: asked again, it is kept, e.g. a
    // torch tensor that requires grad, or a bfloat16 one.)
    py::module_::import("numpy").attr("asarray")(value);
  } catch (py::error_already_set& e) {
    why = " (NumPy cannot read it: " + std::string(py::str(e.value())) + ")";
  }
  throw ConfigError(name + ": expected " + expected + ", got " + py::str(py::type::of(value)).cast<std::string>() + why);
}

std::string rows_text(int rows) { return rows < 0 ? "N" : "N = " + std::to_string(rows); }

void require_float(const py::array& a, const std::string& name, const std::string& expected) {
  if (a.dtype().kind() != 'f') bad_argument(name, expected, a);
}

}  // namespace

Eigen::MatrixX3d vertices_arg(const py::handle& value, const std::string& name, int rows) {
  const std::string expected = "a float array of shape [N, 3]" + (rows < 0 ? std::string() : " (" + rows_text(rows) + ")");
  py::array a = as_array(value, name, expected);
  require_float(a, name, expected);
  if (a.ndim() != 2 || a.shape(1) != 3 || (rows >= 0 && a.shape(0) != rows)) bad_argument(name, expected, a);
  auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
  Eigen::MatrixX3d m(d.shape(0), 3);
  const double* p = d.data();
  for (py::ssize_t i = 0; i < d.shape(0); ++i) m.row(i) << p[3 * i], p[3 * i + 1], p[3 * i + 2];
  return m;
}

Eigen::MatrixX3d finite_vertices_arg(const py::handle& value, const std::string& name, int rows) {
  Eigen::MatrixX3d m = vertices_arg(value, name, rows);
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    if (!m.row(i).allFinite())
      throw ConfigError(name + ": vertex " + std::to_string(i) + " has a non-finite coordinate (NaN or inf)");
  return m;
}

Tensor vertices_batch_arg(const py::handle& value, const std::string& name, int rows, bool* batched) {
  const std::string expected = "a float array of shape [" + rows_text(rows) + ", 3] or [batch, " + std::to_string(rows) + ", 3]";
  py::array a = as_array(value, name, expected);
  require_float(a, name, expected);
  const bool three = a.ndim() == 3;
  if ((a.ndim() != 2 && !three) || a.shape(a.ndim() - 1) != 3 || a.shape(a.ndim() - 2) != rows)
    bad_argument(name, expected, a);
  if (three && a.shape(0) < 1) throw ConfigError(name + ": the batch is empty (" + describe(a) + "): give one body or more");
  if (batched) *batched = three;
  // Read in double and checked before narrowing: a coordinate float32 cannot
  // hold (1e308) was "non-finite vertex coordinates" with no vertex named,
  // and one 1e6 m out was rounded to 6 cm before anything could say so.
  auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
  const int n = three ? static_cast<int>(d.shape(0)) : 1;
  Tensor t(n, rows, 3);
  const double* in = d.data();
  // A sample whose own extent is far beyond a body's is in other units, which
  // the caller's units check names better ("likely millimetres"): only a body
  // of a body's size lying far out is refused here as beyond float32.
  using Rows = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>;
  std::vector<char> body_sized(static_cast<std::size_t>(n));
  for (int b = 0; b < n; ++b) {
    const Rows sample(in + static_cast<std::ptrdiff_t>(b) * rows * 3, rows, 3);
    body_sized[static_cast<std::size_t>(b)] = (sample.colwise().maxCoeff() - sample.colwise().minCoeff()).maxCoeff() <= 0.1 * kFloatExactReach;
  }
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double x = in[k];
    const bool fits_float = std::isfinite(x) && std::abs(x) <= std::numeric_limits<float>::max();
    if (fits_float && (std::abs(x) <= kFloatExactReach || !body_sized[k / 3 / static_cast<std::size_t>(rows)])) {
      t.data()[k] = static_cast<float>(x);
      continue;
    }
    const std::size_t vertex = k / 3 % static_cast<std::size_t>(rows), sample = k / 3 / static_cast<std::size_t>(rows);
    char at[96];
    std::snprintf(at, sizeof at, "vertex %zu (%c = %g)", vertex, "xyz"[k % 3], x);
    const std::string batch = three ? "[" + std::to_string(sample) + "]" : std::string();
    if (!std::isfinite(x))
      throw ConfigError(name + ": non-finite coordinate at " + (three ? batch + " " : "") + at);
    if (std::abs(x) > std::numeric_limits<float>::max())  // (finite: it was called non-finite)
      throw ConfigError(name + ": a coordinate beyond float32's range at " + (three ? batch + " " : "") + at +
                        " (metres: a body is about 2 m tall)");
    const std::string what = name + batch + ": " + at;
    char far[400];
    std::snprintf(far, sizeof far,
                  "%s lies %.0f m from the origin: drape's arrays are float32, which hold coordinates that far only "
                  "to %.2g mm; move it within %.0f m of the origin (and what comes back by the same offset; drape "
                  "predict's command line does this itself)",
                  what.c_str(), std::abs(x), 1e3 * float_rounding(x), kFloatExactReach);
    throw ConfigError(far);
  }
  return t;
}

py::array_t<float> to_numpy(Tensor&& t, bool drop_batch) {
  auto* owned = new Tensor(std::move(t));
  py::capsule free_it(owned, [](void* p) { delete static_cast<Tensor*>(p); });
  std::vector<py::ssize_t> shape{owned->batch(), owned->rows(), owned->cols()};
  if (drop_batch) shape.erase(shape.begin());
  return py::array_t<float>(shape, owned->data(), free_it);
}

// [N, 3] arrays are C-ordered (x0, y0, z0, x1, ...), as the predictions and
// the datasets are: Eigen's column-major order came back Fortran-ordered,
// which np.frombuffer and C readers of the buffer take as x0, x1, ... (an
// outside check). One copy of N x 3 numbers.
using RowMajor3d = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using RowMajor3i = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;

py::array_t<double> to_numpy(Eigen::MatrixX3d&& m) {
  auto* owned = new RowMajor3d(m);
  py::capsule free_it(owned, [](void* p) { delete static_cast<RowMajor3d*>(p); });
  const auto n = static_cast<py::ssize_t>(owned->rows());
  return py::array_t<double>({n, py::ssize_t{3}}, {static_cast<py::ssize_t>(3 * sizeof(double)), py::ssize_t{sizeof(double)}},
                             owned->data(), free_it);
}

py::array_t<double> to_numpy(Eigen::VectorXd&& v) {
  auto* owned = new Eigen::VectorXd(std::move(v));
  py::capsule free_it(owned, [](void* p) { delete static_cast<Eigen::VectorXd*>(p); });
  return py::array_t<double>({static_cast<py::ssize_t>(owned->size())}, owned->data(), free_it);
}

py::array_t<int> to_numpy(Eigen::MatrixX3i&& m) {
  auto* owned = new RowMajor3i(m);
  py::capsule free_it(owned, [](void* p) { delete static_cast<RowMajor3i*>(p); });
  const auto n = static_cast<py::ssize_t>(owned->rows());
  return py::array_t<int>({n, py::ssize_t{3}}, {static_cast<py::ssize_t>(3 * sizeof(int)), py::ssize_t{sizeof(int)}},
                          owned->data(), free_it);
}

py::dict energy_dict(const std::vector<std::pair<std::string, double>>& terms) {
  py::dict d;
  for (const auto& [name, value] : terms) d[py::str(name)] = value;
  return d;
}

namespace {
PyObject* drape_warning = nullptr;
}  // namespace

// The stack level of the first Python frame outside the drape package: a
// warning raised through one of its Python wrappers (Model.optimize,
// drape.simulate) named a line of drape/__init__.py, where a user's warning
// filter by module or line could not find it (an outside check).
namespace {
int caller_stack_level() {
  int level = 1;
  for (py::object frame = py::module_::import("sys").attr("_getframe")(0); !frame.is_none();
       frame = frame.attr("f_back"), ++level) {
    const std::string module = py::str(frame.attr("f_globals").attr("get")("__name__", ""));
    if (module != "drape" && module.rfind("drape.", 0) != 0) break;
  }
  return level;
}
}  // namespace

void warn_python(const std::string& text) {
  if (PyErr_WarnEx(drape_warning ? drape_warning : PyExc_UserWarning, text.c_str(), caller_stack_level()) != 0)
    throw py::error_already_set();  // warnings filtered as errors raise
}

void register_errors(py::module_& m) {
  // Created with the C API so that ConfigError can derive from both drape.Error and ValueError.
  static PyObject* error = PyErr_NewExceptionWithDoc(
      "drape.Error", "A drape failure (the drape program's exit code 1); the message is the program's.", PyExc_RuntimeError,
      nullptr);
  static PyObject* config_bases = PyTuple_Pack(2, error, PyExc_ValueError);
  static PyObject* config_error = PyErr_NewExceptionWithDoc(
      "drape.ConfigError", "Bad configuration, arguments or input files (exit code 2): the caller's to fix.",
      config_bases, nullptr);
  m.attr("Error") = py::handle(error);
  m.attr("ConfigError") = py::handle(config_error);
  // drape::warn's channel (drape/warnings.hpp) as Python warnings of their own category.
  static PyObject* warning = PyErr_NewExceptionWithDoc(
      "drape.DrapeWarning", "A warning of drape's C++ core or its plugins (a UserWarning).", PyExc_UserWarning, nullptr);
  m.attr("DrapeWarning") = py::handle(warning);
  drape_warning = warning;
  set_warning_handler([](const std::string& text) {
    if (!Py_IsInitialized()) return;
    py::gil_scoped_acquire gil;
    warn_python(text);
  });
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const ConfigError& e) {
      PyErr_SetString(config_error, e.what());
    } catch (const Error& e) {
      PyErr_SetString(error, e.what());
    }
  });
}

std::optional<double> real_number(const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) return std::nullopt;
  const py::module_ numpy = py::module_::import("numpy");
  if (py::isinstance(value, numpy.attr("bool_"))) return std::nullopt;
  if (!py::isinstance(value, py::module_::import("numbers").attr("Real"))) return std::nullopt;
  return value.cast<double>();
}

double number_arg(const py::handle& value, const std::string& name) {
  if (const std::optional<double> number = real_number(value)) return *number;
  throw ConfigError(name + ": expected a number, got " + py::str(py::type::of(value)).cast<std::string>() +
                    (py::isinstance<py::bool_>(value) ? " (True is not 1.0 here)" : ""));
}

BodyRequest body_request(const py::handle& bmi, const py::handle& height, const py::handle& sex, const py::dict& girths,
                         const std::string& model_name) {
  BodyRequest request;
  // (Typed double, a bool was taken: sex=True made a man, bmi=True was "BMI 1 is outside the range": an outside check.)
  request.bmi = number_arg(bmi, "bmi");
  request.height = number_arg(height, "height");
  request.sex = number_arg(sex, "sex");
  for (const auto& [key, value] : girths) {
    if (key.cast<std::string>() == "pose")
      throw ConfigError("pose: this makes the body at rest (its shape); pose it with drape.body(..., pose=...), or "
                            "give the pose to Model.predict(body, pose=...), which poses the body at rest (docs/poses.md)");
    const std::optional<double> number = real_number(value);
    if (!number)
      throw ConfigError(key.cast<std::string>() + ": expected a number (a proportion of body model '" + model_name +
                            "'), got " + py::str(py::type::of(value)).cast<std::string>());
    request.proportions[key.cast<std::string>()] = *number;
  }
  return request;
}

// pose=None: none; "name=degrees,..." or {name: degrees}: that pose
// (docs/poses.md), ValueError naming the angle when it is unknown, NaN or out
// of range, or the body model has no skeleton.
std::optional<Pose> pose_arg(const BodyModel& model, const std::string& model_name, const py::handle& pose) {
  if (pose.is_none()) return std::nullopt;
  if (!model.poseable())
    throw ConfigError("pose: body " + model_name + " has no skeleton, so it cannot be posed "
                      "(docs/poses.md says which models can)");
  if (py::isinstance<py::str>(pose)) return parse_pose(pose.cast<std::string>(), model.pose_angles(), "pose");
  if (!py::isinstance<py::dict>(pose)) throw ConfigError("pose: expected a dict {name: degrees} or a string 'name=degrees,...'");
  std::string text;
  for (const auto& [name, value] : pose.cast<py::dict>()) {
    if (!py::isinstance<py::str>(name)) throw ConfigError("pose: joint angle names are strings");
    double degrees = 0;
    // (A bool casts to 0 or 1 degree: True is a mistake, not an angle.)
    if (py::isinstance<py::bool_>(value))
      throw ConfigError("pose: " + name.cast<std::string>() + " wants a number of degrees, not " +
                        (value.cast<bool>() ? "True" : "False"));
    try {
      degrees = value.cast<double>();
    } catch (const py::cast_error&) {
      throw ConfigError("pose: " + name.cast<std::string>() + " wants a number of degrees");
    }
    std::ostringstream item;
    item.precision(17);
    item << name.cast<std::string>() << "=" << degrees << ",";
    text += item.str();
  }
  return parse_pose(text, model.pose_angles(), "pose");
}

}  // namespace drape::python
