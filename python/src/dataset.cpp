// Datasets of drape generate: make one (the same service as drape generate),
// open, list samples by split, read a batch.
#include "common.hpp"

#include <drape/io/dataset.hpp>
#include <drape/services/dataset_generation.hpp>

#include <cmath>
#include <iostream>
#include <type_traits>

namespace drape::python {
namespace {

std::vector<std::size_t> indices_arg(const DatasetReader& r, const py::handle& value) {
  const std::string expected = "an integer array of sample indices [n] (0 <= i < " + std::to_string(r.size()) + ", done samples)";
  py::array a = py::array::ensure(value);
  if (a && a.ndim() == 1 && a.size() == 0) return {};  // [] (NumPy makes an empty list float): no samples
  if (!a || (a.dtype().kind() != 'i' && a.dtype().kind() != 'u') || a.ndim() != 1)
    throw ConfigError("indices: expected " + expected + (a ? ", got " + describe(a) : std::string()));
  std::vector<std::size_t> out;
  // Each index read in its own signedness: forcecast to int64, an unsigned
  // 2**63 + 5 was refused as "sample -9223372036854775803".
  const auto take_all = [&](auto tag) {
    using Index = decltype(tag);
    const auto indices = py::array_t<Index, py::array::c_style | py::array::forcecast>::ensure(a);
    for (py::ssize_t k = 0; k < indices.shape(0); ++k) {
      const Index i = indices.data()[k];
      bool done = false;
      if constexpr (std::is_signed_v<Index>) done = i >= 0 && static_cast<std::size_t>(i) < r.size();
      else done = i < r.size();
      done = done && r.done()[static_cast<std::size_t>(i)];
      if (!done)
        throw ConfigError("indices: sample " + std::to_string(i) + " is not a done sample of this dataset (it has " +
                              std::to_string(r.size()) + ")");
      out.push_back(static_cast<std::size_t>(i));
    }
  };
  if (a.dtype().kind() == 'u') take_all(static_cast<unsigned long long>(0));
  else take_all(static_cast<long long>(0));
  return out;
}

py::array_t<long long> index_array(const std::vector<std::size_t>& v) {
  std::vector<long long> out(v.begin(), v.end());
  return to_numpy(std::move(out));
}

SampleRange range_arg(const py::handle& value, const std::string& name) {
  const std::string expected = "a number or a (lo, hi) pair with lo <= hi";
  try {
    // A pair as a tuple, a list or a NumPy array of two.
    if (py::isinstance<py::tuple>(value) || py::isinstance<py::list>(value) ||
        (py::isinstance<py::array>(value) && py::reinterpret_borrow<py::array>(value).ndim() == 1)) {
      // (Each a real number: True was taken as 1.0, as it was for one number.)
      const py::sequence items = py::reinterpret_borrow<py::sequence>(value);
      std::vector<double> pair;
      for (const py::handle item : items)
        if (const std::optional<double> number = real_number(item)) pair.push_back(*number);
        else pair.push_back(std::nan(""));
      if (pair.size() == 2 && pair[0] <= pair[1]) return {pair[0], pair[1]};
    } else if (const std::optional<double> v = real_number(value); v && *v == *v) {
      return {*v, *v};
    }
  } catch (const py::cast_error&) {
  }
  throw ConfigError(name + ": expected " + expected + ", got " + py::repr(value).cast<std::string>());
}

py::dict generate(const PyScene& scene, const std::string& out, std::size_t count, const py::handle& bmi,
                  const py::handle& height, const py::handle& sex, double girths, std::uint64_t seed,
                  const std::pair<std::size_t, std::size_t>& shard, int threads, bool progress, bool draw_poses,
                  const std::string& pose_ranges) {
  GenerateRequest request;  // generate_dataset checks it (ConfigError: ValueError)
  request.draw_poses = draw_poses;
  request.pose_ranges = pose_ranges;
  request.count = count;
  request.bmi = range_arg(bmi, "bmi");
  request.height = range_arg(height, "height");
  request.sex = range_arg(sex, "sex");
  request.girths = girths;
  request.seed = seed;
  request.shard = Shard{shard.first, shard.second};
  request.threads = threads;
  GenerateObserver observer;
  if (progress) observer.progress = &std::cerr;
  GeneratePlan plan;
  observer.on_start = [&](const GeneratePlan& p) { plan = p; };
  if (in_python_main_thread()) observer.poll = [] { check_python_signals(); };
  GenerateSummary done;
  try {
    py::gil_scoped_release release;
    done = generate_dataset(registry(), scene.simulation->scene(), request, out, observer);
  } catch (const PythonSignal&) {
    throw py::error_already_set();  // KeyboardInterrupt, as PyErr_CheckSignals set it; the samples done are kept
  }
  py::dict d;
  d["out"] = out;
  d["samples"] = done.samples;
  d["first"] = plan.first;
  d["resumed_with"] = plan.already;
  d["threads"] = plan.threads;
  d["not_settled"] = done.not_settled;
  d["penetrating"] = done.penetrating;
  d["crossing"] = done.crossing;
  d["crossing_itself"] = done.crossing_itself;
  d["checked_again"] = done.checked_again;  // drapes of earlier runs read back to count those crossing themselves
  d["ranges"] = plan.ranges;
  d["already_finished"] = done.already_finished;  // this same request had finished it: nothing simulated
  return d;
}

}  // namespace

void register_dataset(py::module_& m) {
  m.def("_generate", &generate, py::arg("scene"), py::arg("out"), py::arg("count"), py::arg("bmi"), py::arg("height"),
        py::arg("sex"), py::arg("girths"), py::arg("seed"), py::arg("shard"), py::arg("threads"), py::arg("progress"),
        py::arg("draw_poses"), py::arg("pose_ranges"));
  m.def(
      "dataset_name", [](const std::string& path) { return dataset_name(path); }, py::arg("path"),
      "What a model records as the data it was trained on: a file's name, or a glob pattern whole (as drape model "
      "info shows it).");
  py::class_<DatasetReader>(m, "Dataset",
                            "A dataset file of drape generate (or a .partial one: its done samples), or a glob pattern "
                            "of shard files read as one; slim files' bodies are rebuilt from their shape parameters.")
      .def(py::init([](const std::string& path) {
             py::gil_scoped_release release;
             return std::make_unique<DatasetReader>(path);
           }),
           py::arg("path"))
      .def("__len__", [](const DatasetReader& r) { return r.indices().size(); }, "done samples")
      .def_property_readonly("size", &DatasetReader::size, "samples the file was made for, done or not")
      .def_property_readonly("layout", [](const DatasetReader& r) {
        const DatasetLayout& l = r.layout();
        py::dict d;
        d["samples"] = l.samples;
        d["body_params"] = l.body_params;
        d["body_vertices"] = l.body_vertices;
        d["garment_vertices"] = l.garment_vertices;
        d["stats"] = l.stats;
        d["scene"] = l.scene;
        d["template_hash"] = l.template_hash;
        d["drape_version"] = l.drape_version;
        d["created"] = l.created;
        d["attributes"] = l.attributes;
        d["body_vertices_stored"] = l.body_vertices_stored;
        d["pose_angles"] = l.pose_angles;  // empty: A-pose bodies
        return d;
      })
      .def_property_readonly(
          "files",
          [](const DatasetReader& r) {
            std::vector<std::string> out;
            for (const auto& f : r.files()) out.push_back(f.string());
            return out;
          },
          "the file, or the files the pattern matched, in the order their samples are numbered")
      .def_property_readonly(
          "faces",
          [](const DatasetReader& r) -> py::object {
            Eigen::MatrixX3i faces = r.layout().garment_faces;
            if (faces.rows() == 0) return py::none();
            return to_numpy(std::move(faces));
          },
          "the garment template's triangles, int32 [F, 3] (/garments/faces), or None for a file written before "
          "datasets carried them")
      .def("indices", [](const DatasetReader& r, const std::string& splits) { return index_array(r.indices(splits)); },
           py::arg("split") = "all", "done samples of 'train', 'val', 'test', 'train,val' or 'all', in file order")
      .def(
          "read",
          [](const DatasetReader& r, const py::handle& indices) {
            const auto idx = indices_arg(r, indices);
            Tensor body, garment, params, poses;
            const bool posed = !r.layout().pose_angles.empty();
            {
              py::gil_scoped_release release;
              body = r.body_vertices(idx);
              garment = r.garment_vertices(idx);
              params = r.body_params(idx);
              if (posed) poses = r.poses(idx);
            }
            std::vector<std::int8_t> splits;
            for (auto i : idx) splits.push_back(r.splits()[i]);
            py::dict d;
            d["indices"] = index_array(idx);
            d["body"] = to_numpy(std::move(body), false);
            d["garment"] = to_numpy(std::move(garment), false);
            const int n = params.batch(), p = params.cols();
            d["body_params"] = to_numpy(std::move(params), false).reshape({n, p});
            d["split"] = to_numpy(std::move(splits));
            if (posed) {
              const int a = poses.cols();
              d["pose"] = to_numpy(std::move(poses), false).reshape({n, a});
            }
            return d;
          },
          py::arg("indices"),
          "A batch: body float32 [n, Nb, 3], garment float32 [n, Ng, 3], body_params float32 [n, P], split int8 [n] "
          "(0 train, 1 val, 2 test), and in a posed dataset pose float32 [n, A] (degrees, layout['pose_angles'] order)")
      .def(
          "posing",
          [](const DatasetReader& r, const py::handle& indices) {
            const auto idx = indices_arg(r, indices);
            DatasetReader::Posing posing;
            {
              py::gil_scoped_release release;
              posing = r.posing(idx);
            }
            py::dict d;
            const int n = posing.angles.batch(), a = posing.angles.cols();
            d["unposed"] = to_numpy(std::move(posing.unposed), false);
            d["transforms"] = to_numpy(std::move(posing.transforms), false);
            d["angles"] = to_numpy(std::move(posing.angles), false).reshape({n, a});
            return d;
          },
          py::arg("indices"),
          "What a posed model's graph reads (docs/poses.md): unposed float32 [n, Nb, 3] (each body at rest), transforms "
          "float32 [n, J, 12] (each joint's rigid transform into the sample's pose: R row by row, then t) and angles "
          "float32 [n, A] (radians, the body model's pose_angles order); an A-pose dataset's samples are at rest. Made "
          "by the stored scene's body model once per sample (20-90 ms each) and kept.")
      .def(
          "stat",
          [](const DatasetReader& r, const std::string& name, const py::handle& indices) {
            return to_numpy(r.stat(name, indices_arg(r, indices)));
          },
          py::arg("name"), py::arg("indices"), "a per-sample statistic (layout['stats'] names them)");
}

}  // namespace drape::python
