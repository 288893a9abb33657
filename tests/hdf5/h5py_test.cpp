// The documented layouts as h5py sees them (docs/formats.md). Runs only where
// python3 has h5py; elsewhere it says it was skipped (nothing is installed).
#include <catch2/catch.hpp>

#include "test_support.hpp"

#include <drape/io/checkpoint.hpp>
#include <drape/io/dataset.hpp>

#include <fstream>

using namespace drape;
using drape::test::TempDir;

TEST_CASE("h5py reads datasets and checkpoints with the documented layout", "[hdf5][h5py]") {
  std::string output;
  // Debian's interpreter first: a python3 earlier on PATH (pyenv) may lack h5py.
  std::string python;
  for (const char* candidate : {"/usr/bin/python3", "python3"})
    if (test::run(std::string(candidate) + " -c 'import h5py'", output) == 0) {
      python = candidate;
      break;
    }
  if (python.empty()) {
    WARN("skipped: python3 cannot import h5py on this machine (not installed; the test installs nothing)");
    return;
  }
  TempDir dir;
  DatasetLayout layout;
  layout.samples = 2;
  layout.body_params = 3;
  layout.body_vertices = 4;
  layout.garment_vertices = 5;
  layout.stats = {"energy"};
  layout.scene = "effects: [gravity]\n";
  layout.template_hash = "h";
  {
    DatasetWriter writer(dir / "data.h5", layout);
    for (std::size_t i = 0; i < 2; ++i) {
      DatasetSample s;
      s.body_params = Eigen::VectorXf::Constant(3, static_cast<float>(i));
      s.body_vertices = MatrixRM::Constant(4, 3, 1.5f);
      s.garment_vertices = MatrixRM::Constant(5, 3, 2.5f);
      s.split = Split::Test;
      s.stats = {{"energy", 0.25}};
      writer.write(i, s);
    }
    writer.finish();
  }
  Weight w;
  w.value = Tensor(1, 2, 3, 0.5f);
  w.grad = Tensor(1, 2, 3);
  save_checkpoint(dir / "model.h5", NamedWeights{{"encoder/w", &w}}, Checkpoint{"nodes: {}\n", {{"epoch", "7"}}, std::nullopt, {}});

  std::ofstream(dir / "check.py") << R"(import sys, h5py, numpy as np
d = h5py.File(sys.argv[1], 'r')
assert d['bodies/params'].shape == (2, 3) and d['bodies/params'].dtype == np.float32
assert d['bodies/vertices'].shape == (2, 4, 3) and d['garments/vertices'].shape == (2, 5, 3)
assert d['split'].dtype == np.int8 and list(d['split'][:]) == [2, 2]
assert d['done'].dtype == np.uint8 and d['done'][:].all()
assert d['stats/energy'].dtype == np.float64 and d['stats/energy'][1] == 0.25
# Strings are fixed-length UTF-8 (h5_attributes.cpp says why): h5py gives bytes.
for key in ('scene', 'template_hash', 'drape_version', 'created', 'format'):
    assert isinstance(d.attrs[key], bytes), key
assert d.attrs['scene'].decode() == 'effects: [gravity]\n'
# Sealed: the file's CRC-32 in its 512-byte user block, which h5py skips.
assert d.userblock_size == 512 and open(sys.argv[1], 'rb').read(20) == b'drape sealed hdf5 1\n'
m = h5py.File(sys.argv[2], 'r')
assert m['weights/encoder/w'].shape == (2, 3) and m['weights/encoder/w'].dtype == np.float32
assert (m['weights/encoder/w'][:] == 0.5).all()
assert m.attrs['graph'].decode() == 'nodes: {}\n' and m['meta'].attrs['epoch'].decode() == '7'
print('ok')
)";
  const int code = test::run(python + " " + (dir / "check.py").string() + " " + (dir / "data.h5").string() + " " +
                                 (dir / "model.h5").string(),
                             output);
  INFO(output);
  CHECK(code == 0);
  CHECK(output == "ok\n");
}
