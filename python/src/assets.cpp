// Garment templates and their precomputed assets: drape.assets(...) and
// Model.assets. Arrays are read-only views of the cached assets (no copies);
// sparse matrices come as COO arrays, turned into SciPy's by drape/__init__.py.
#include "common.hpp"

#include <drape/energy.hpp>
#include <drape/assets/assets.hpp>

namespace drape::python {

struct PyAssets {
  std::shared_ptr<const Assets> assets;
};

py::object wrap_assets(std::shared_ptr<const Assets> assets) { return py::cast(PyAssets{std::move(assets)}); }

namespace {

std::map<std::string, std::string> string_map(const py::dict& d) {
  std::map<std::string, std::string> out;
  for (const auto& [k, v] : d)
    out[k.cast<std::string>()] = py::isinstance<py::bool_>(v) ? (v.cast<bool>() ? "true" : "false") : py::str(v).cast<std::string>();
  return out;
}

py::dict level_dict(const geometry::HierarchyLevel& level, py::handle owner) {
  py::dict d;
  d["vertices"] = view(level.mesh.vertices, owner);
  d["faces"] = view(level.mesh.faces, owner);
  d["uv"] = view(level.mesh.uv, owner);
  d["uv_faces"] = view(level.mesh.uv_faces, owner);
  d["fine_index"] = view(level.fine_index, owner);
  d["upsample"] = level.upsample.size() ? py::object(coo(level.upsample)) : py::none();
  return d;
}

}  // namespace

void register_assets(py::module_& m) {
  py::class_<PyAssets>(m, "_Assets")
      .def_property_readonly("garment_vertices", [](py::object self) { return view(self.cast<PyAssets&>().assets->garment->mesh.vertices, self); },
                             "float64 [Ng, 3]: the template dressed on the mean body (rest and start state)")
      .def_property_readonly("garment_faces", [](py::object self) { return view(self.cast<PyAssets&>().assets->garment->mesh.faces, self); })
      .def_property_readonly("garment_uv", [](py::object self) { return view(self.cast<PyAssets&>().assets->garment->mesh.uv, self); },
                             "float64 [T, 2]: material space (UV in metres), indexed per corner by garment_uv_faces")
      .def_property_readonly("garment_uv_faces", [](py::object self) { return view(self.cast<PyAssets&>().assets->garment->mesh.uv_faces, self); })
      .def_property_readonly("body_vertices", [](py::object self) { return view(self.cast<PyAssets&>().assets->body.vertices, self); },
                             "float64 [Nb, 3]: the mean body")
      .def_property_readonly("body_faces", [](py::object self) { return view(self.cast<PyAssets&>().assets->body.faces, self); })
      .def_property_readonly("correspondence", [](py::object self) {
             const auto& c = self.cast<PyAssets&>().assets->correspondence;
             return view<int>(c.data(), {static_cast<py::ssize_t>(c.size())}, {sizeof(int)}, self);
           }, "int32 [Ng]: the body vertex each garment vertex is tied to")
      .def_property_readonly("hierarchy", [](py::object self) {
             py::list levels;
             for (const auto& l : self.cast<PyAssets&>().assets->hierarchy.levels) levels.append(level_dict(l, self));
             return levels;
           }, "levels finest first: dicts of vertices, faces, uv, uv_faces, fine_index, upsample (to this level from the next)")
      .def_property_readonly("_laplacians", [](const PyAssets& a) {
             py::list out;
             for (const auto& l : a.assets->laplacians) out.append(coo(l));
             return out;
           })
      .def_property_readonly("eigenvalues", [](py::object self) { return view(self.cast<PyAssets&>().assets->eigenvalues, self); })
      .def_property_readonly("eigenvectors", [](py::object self) { return view(self.cast<PyAssets&>().assets->eigenvectors, self); },
                             "float32 [Ng, k]: orthonormal columns, ascending eigenvalue")
      .def_property_readonly("hash", [](const PyAssets& a) { return a.assets->hash; })
      .def_property_readonly("spec", [](const PyAssets& a) { return a.assets->spec_text; })
      .def_property_readonly("dims", [](const PyAssets& a) { return a.assets->dims(); });

  m.def(
      "_assets",
      [](const std::string& garment, const py::dict& garment_params, const std::string& body_model, const py::dict& body_params,
         int eigen_k, int levels, const std::optional<std::string>& cache_dir) {
        AssetsSpec spec;
        spec.garment = garment;
        spec.garment_params = string_map(garment_params);
        spec.body_model = body_model;
        spec.body_params = string_map(body_params);
        spec.eigen_k = eigen_k;
        spec.levels = levels;
        std::shared_ptr<const Assets> a;
        {
          py::gil_scoped_release release;
          a = build_assets(registry(), spec, cache_dir ? std::filesystem::path(*cache_dir) : default_cache_dir());
        }
        return PyAssets{a};
      },
      py::arg("garment"), py::arg("garment_params"), py::arg("body_model"), py::arg("body_params"), py::arg("eigen_k"),
      py::arg("levels"), py::arg("cache_dir"));
}

}  // namespace drape::python
