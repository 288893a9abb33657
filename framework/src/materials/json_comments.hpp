#pragma once
// ArcSim's material files are read by jsoncpp, which accepts `//` and `/* */`
// comments (aluminium.json and paper.json start with `//` lines); drape reads
// them with yaml-cpp, which does not. Framework-internal.
#include <string>

namespace drape::materials_detail {

// `text` with every comment outside a string replaced by spaces (newlines
// kept), so that yaml-cpp's line numbers are still the file's. Tabs outside
// strings become spaces too: JSON allows them as white space, YAML's flow
// context does not everywhere.
std::string blank_json_comments(const std::string& text);

}  // namespace drape::materials_detail
