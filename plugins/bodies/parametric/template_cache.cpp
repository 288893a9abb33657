#include "template_cache.hpp"

#include <drape/assets/assets.hpp>
#include <drape/errors.hpp>
#include <drape/fnv1a.hpp>
#include <drape/io/atomic_file.hpp>
#include <drape/io/h5.hpp>

#include <dlfcn.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <system_error>
#include <vector>

namespace drape::parametric {
namespace fs = std::filesystem;
namespace {

using RowMajor3d = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using RowMajor3i = Eigen::Matrix<std::int32_t, Eigen::Dynamic, 3, Eigen::RowMajor>;

// The library holding `address`: its path, and its path with its size and
// modification time (empty when unknown, in a static build: then no cache).
struct LibraryStamp {
  std::string path, stamp;
};

LibraryStamp library_stamp(const void* address) {
  Dl_info info{};
  if (!dladdr(address, &info) || !info.dli_fname) return {};
  std::error_code ec;
  const fs::path path = fs::canonical(info.dli_fname, ec);
  if (ec) return {};
  const auto size = fs::file_size(path, ec);
  if (ec) return {};
  const auto time = fs::last_write_time(path, ec);
  if (ec) return {};
  std::ostringstream o;
  o << path.string() << " " << size << " " << time.time_since_epoch().count();
  return {path.string(), o.str()};
}

bool debug() { return std::getenv("DRAPE_BODY_DEBUG") != nullptr; }

// The cached mesh when the file holds this key and a sound mesh; false otherwise.
bool load(const fs::path& file, const std::string& key, BodyTemplate& t) {
  std::error_code ec;
  if (!fs::exists(file, ec)) return false;
  try {
    const h5::File f = h5::File::open(file);
    if (f.string_attribute("/", "key") != key) return false;
    h5::Dims vdims, fdims;
    const std::vector<double> v = f.read<double>("vertices", &vdims);
    const std::vector<std::int32_t> faces = f.read<std::int32_t>("faces", &fdims);
    if (vdims.size() != 2 || vdims[1] != 3 || fdims.size() != 2 || fdims[1] != 3 || vdims[0] < 4 || fdims[0] < 4) return false;
    const auto nv = static_cast<Eigen::Index>(vdims[0]), nf = static_cast<Eigen::Index>(fdims[0]);
    t.vertices = Eigen::Map<const RowMajor3d>(v.data(), nv, 3);
    t.faces = Eigen::Map<const RowMajor3i>(faces.data(), nf, 3).cast<int>();
    return t.vertices.allFinite() && t.faces.minCoeff() >= 0 && t.faces.maxCoeff() < nv;
  } catch (const std::exception& e) {
    if (debug()) std::fprintf(stderr, "template cache: %s: %s\n", file.c_str(), e.what());
    return false;
  }
}

void save(const fs::path& file, const std::string& key, const BodyTemplate& t) {
  try {
    fs::create_directories(file.parent_path());
    const RowMajor3d v = t.vertices;
    const RowMajor3i faces = t.faces.cast<std::int32_t>();
    write_atomically(file, [&](const fs::path& tmp) {
      h5::File f = h5::File::create(tmp);
      f.write("vertices", {static_cast<std::size_t>(v.rows()), 3}, v.data());
      f.write("faces", {static_cast<std::size_t>(faces.rows()), 3}, faces.data());
      f.set_attribute("/", "key", key);
      f.close();
    });
  } catch (const std::exception& e) {  // only a cache: the next process meshes again
    if (debug()) std::fprintf(stderr, "template cache: cannot write %s: %s\n", file.c_str(), e.what());
  }
}

}  // namespace

TemplateCacheKey template_cache_key(int target_vertices, Rig rig) {
  const LibraryStamp plugin = library_stamp(reinterpret_cast<const void*>(&cached_template));
  const LibraryStamp framework = library_stamp(reinterpret_cast<const void*>(&default_cache_dir));
  if (plugin.stamp.empty() || framework.stamp.empty()) return {};
  std::ostringstream which, key;
  which << "parametric body template 1; rig " << static_cast<int>(rig) << "; target " << target_vertices;
  // One file per build and rig (a rebuild rewrites it rather than adding one).
  TemplateCacheKey out;
  out.file_name = "parametric-template-" + Fnv1a().text(which.str() + "; " + plugin.path + "; " + framework.path).hex() + ".h5";
  key << which.str() << "; plugin " << plugin.stamp << "; framework " << framework.stamp;
  out.key = key.str();
  return out;
}

BodyTemplate cached_template(int target_vertices, Rig rig) {
  const TemplateCacheKey which = template_cache_key(target_vertices, rig);
  if (which.key.empty()) return build_template(target_vertices, rig);
  const fs::path file = default_cache_dir() / which.file_name;
  const std::string& key = which.key;
  BodyTemplate t;
  t.rig = rig;
  t.mean = plan_body(mean_shape_vector(), rig);
  if (load(file, key, t)) {
    finish_template(t);
    return t;
  }
  t = build_template(target_vertices, rig);
  save(file, key, t);
  return t;
}

}  // namespace drape::parametric
