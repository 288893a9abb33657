// ArcSim material files (materials/*.json): reading one as a preset, loading
// one as a material, and writing a scene's file references out as data.
#include <drape/materials/materials.hpp>

#include "json_comments.hpp"
#include "material_validation.hpp"
#include "../yaml_util.hpp"

#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace drape {
namespace materials_detail {

fs::path relative_to(const std::string& naming_file, const std::string& path) {
  const fs::path p(path);
  if (p.is_absolute()) return p;
  return (fs::path(naming_file).parent_path() / p).lexically_normal();
}

bool names_arcsim_file(const std::string& spec) {
  constexpr std::string_view suffix = ".json";
  return spec.size() > suffix.size() && spec.compare(spec.size() - suffix.size(), suffix.size(), suffix) == 0;
}

MaterialPreset read_arcsim_file(const fs::path& path, const std::string& name, const SourceLocation& named_at) {
  const auto unreadable = [&](const std::string& why) {
    return ConfigError(named_at, "cannot read ArcSim material file '" + path.string() + "': " + why);
  };
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw unreadable("it is a directory");
  std::ifstream in(path);
  if (!in) throw unreadable(std::strerror(errno));
  std::stringstream text;
  text << in.rdbuf();
  if (in.bad()) throw unreadable(std::strerror(errno));
  // Blanking keeps every line where it was: yaml-cpp's lines are the file's.
  const std::string file = path.string();
  const YAML::Node root = yaml::load_text(blank_json_comments(text.str()), file);
  return parse_arcsim_file_body(name, root, file);
}

}  // namespace materials_detail

namespace {

// The shortest text that reads back as the same double: 0.187, not
// yaml-cpp's 0.18700000000000000 (17 digits), in a scene people read.
YAML::Node number_node(double v) {
  char text[64];
  const auto end = std::to_chars(text, text + sizeof text, v).ptr;
  return YAML::Node(std::string(text, end));
}

}  // namespace

Material load_arcsim_material(const fs::path& path) {
  const MaterialPreset p = materials_detail::read_arcsim_file(path, path.stem().string(), {path.string(), 0});
  return materials_detail::complete_material(p);
}

YAML::Node self_contained_material_spec(const YAML::Node& spec, const std::string& file) {
  using namespace materials_detail;
  MaterialPreset p;
  if (spec && spec.IsScalar() && names_arcsim_file(spec.Scalar()))
    p = read_arcsim_file(relative_to(file, spec.Scalar()), "", yaml::at(file, spec));
  else if (spec && spec.IsMap() && spec["file"])
    p = parse_material_preset("", spec, file, yaml::at(file, spec));  // multipliers already applied to the data
  else
    return spec;

  YAML::Node out(YAML::NodeType::Map);
  out["model"] = "arcsim";
  out["density"] = number_node(*p.density);
  YAML::Node stretching(YAML::NodeType::Sequence), bending(YAML::NodeType::Sequence);
  for (const Eigen::Vector4d& row : *p.stretching) {
    YAML::Node r(YAML::NodeType::Sequence);
    for (int c = 0; c < 4; ++c) r.push_back(number_node(row[c]));
    stretching.push_back(r);
  }
  for (const auto& row : *p.bending_table) {
    YAML::Node r(YAML::NodeType::Sequence);
    for (const double b : row) r.push_back(number_node(b));
    bending.push_back(r);
  }
  out["stretching"] = stretching;
  out["bending"] = bending;
  out["thickness"] = number_node(*p.thickness);
  return out;
}

}  // namespace drape
