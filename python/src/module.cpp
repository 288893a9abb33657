// The compiled part of the drape Python package (drape/_drape.*.so); the
// package's __init__.py re-exports it with the Python-side conveniences.
#include "common.hpp"

PYBIND11_MODULE(_drape, m) {
  m.doc() = "drape's C++ core: bodies, garment assets, models, scenes, energies, datasets";
  m.attr("__version__") = "0.1.0";
  drape::python::register_errors(m);
  drape::python::register_bodies(m);
  drape::python::register_assets(m);
  drape::python::register_model(m);
  drape::python::register_scene(m);
  drape::python::register_dataset(m);
}
