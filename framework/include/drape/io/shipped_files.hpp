#pragma once
// Files shipped with drape -- scenes, graphs, materials, models -- found by the
// name they have in the source tree ("graphs/scenes/tshirt.yaml",
// "models/tshirt-coarse.h5") from any folder, so that an installed drape (or a
// pip-installed Python package) runs the README's commands as written.
//
// A name that exists relative to the current folder (or is absolute) is used
// as it is; otherwise it is looked for, in order, under
//   1. $DRAPE_DATA_DIR (one folder laid out as the source tree),
//   2. <prefix>/share/drape, the prefix being the one the framework library
//      was loaded from (<prefix>/lib/libdrape_framework.so: cmake --install, and
//      the copy inside the pip-installed package),
//   3. the source tree this library was built from (a build-tree run).
#include <filesystem>
#include <vector>

namespace drape {

// The folders searched, in that order (those that exist).
std::vector<std::filesystem::path> shipped_data_dirs();

// `name` when it exists as given; else the first <dir>/name that exists among
// shipped_data_dirs() (only for a relative name); else an empty path.
std::filesystem::path locate_shipped_file(const std::filesystem::path& name);

// locate_shipped_file, or a ConfigError naming the file and where it looked:
// "graphs/scenes/nope.yaml: no such file (looked in /home/me, /usr/local/share/drape, ...)".
std::filesystem::path find_input_file(const std::filesystem::path& name);

}  // namespace drape
