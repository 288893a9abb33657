#pragma once
// The template kept on disk between processes. Meshing the mean body costs
// about 0.15 s, paid by every process that makes a parametric body (each
// drape body, predict, simulate, and every test that starts one); read back
// it costs a few milliseconds. The file is an assets cache
// (default_cache_dir(): $DRAPE_CACHE_DIR, else ~/.cache/drape), named by a
// key that changes whenever the code that meshes it may have: the rig, the
// vertex target, and the size and modification time of the plugin's and the
// framework's libraries (the file is named by the rig and the libraries'
// paths, so a rebuild rewrites it). A file that is missing, unreadable or
// of another key is meshed again and rewritten (atomically); a cache folder
// that cannot be written is only slower. The layout, for h5py users: /vertices f64
// [N, 3], /faces i32 [F, 3], attribute "key" on /.
#include "body_template.hpp"

#include <filesystem>
#include <string>

namespace drape::parametric {

// The template of build_template(target_vertices, rig), bit for bit, from
// the cache when it holds it.
BodyTemplate cached_template(int target_vertices, Rig rig);

// The file a template is kept in (one per build and rig) and the key it must
// hold to be used; both empty when the libraries cannot be found.
struct TemplateCacheKey {
  std::string file_name, key;
};
TemplateCacheKey template_cache_key(int target_vertices, Rig rig);

}  // namespace drape::parametric
