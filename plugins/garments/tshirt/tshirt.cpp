// The procedural T-shirt template (plugin kind "garment"): a front and a back
// T-shaped panel with half-sleeves, sewn at the shoulders/top of the sleeves and
// under the arms/along the sides, placed around a canonical torso (see
// placement.hpp; drape::dress fits it to a specific body).
#include "tshirt_mesh.hpp"

#include <drape/errors.hpp>
#include <drape/bodies/body.hpp>
#include <drape/plugin.hpp>

#include <cctype>
#include <string>
#include <vector>

namespace {

using namespace drape;

int parse_resolution(const std::string& text) {
  if (text == "default") return 3500;
  if (text == "coarse") return 1000;
  std::size_t used = 0;
  long count = -1;
  try {
    count = std::stol(text, &used);
  } catch (const std::exception&) {
  }
  if (used != text.size() || count < 300 || count > 50000)
    throw ConfigError("resolution '" + text +
                      "' is neither 'default', 'coarse' nor a vertex count between 300 and 50000");
  return static_cast<int>(count);
}

class TshirtSource final : public GarmentSource {
 public:
  explicit TshirtSource(tshirt::TshirtOptions options) : options_(std::move(options)) {}
  Garment build() const override { return tshirt::build_tshirt(options_).garment; }

 private:
  tshirt::TshirtOptions options_;
};

// The graded sizes, smallest first, and "auto".
std::vector<std::string> size_choices() {
  std::vector<std::string> names = tshirt::size_names();
  names.push_back("auto");
  return names;
}

PluginList plugins() {
  const tshirt::TorsoFrame torso;
  PluginDescriptor d;
  d.kind = "garment";
  d.name = "tshirt";
  d.doc = "Procedural T-shirt: two sewn T-shaped panels with half-sleeves, UV in meters, optional front print.";
  d.params = {
      {.name = "size", .type = ParamType::String, .default_value = "regular",
       .doc = "pattern size: the regular pattern graded in width and length by 3xsmall 0.6, 2xsmall 0.7, xsmall 0.8, small 0.9, large 1.12, xlarge 1.25, 2xlarge "
              "1.4, 3xlarge 1.55, 4xlarge 1.7, 5xlarge 1.85, 6xlarge 2.0 (same topology); auto: drape simulate and generate pick the size for each body "
              "(docs/garments.md)", .choices = size_choices()},
      {.name = "resolution", .type = ParamType::String, .default_value = "default",
       .doc = "default (~3.5k vertices), coarse (~1k) or a vertex count"},
      {.name = "print", .type = ParamType::Bool, .default_value = "false",
       .doc = "front print region with its own material (id 1)"},
      {.name = "print_polygon", .type = ParamType::FloatList, .default_value = "[0.35, 0.5, 0.65, 0.5, 0.65, 0.78, 0.35, 0.78]",
       .doc = "print outline x0, y0, x1, y1, ... in the front panel's normalised [0,1]^2 coordinates",
       .min = 0.0, .max = 1.0},
      {.name = "torso_half_width", .type = ParamType::Float, .default_value = std::to_string(torso.half_width),
       .doc = "canonical torso: chest half-width, m", .min = 0.05, .max = 1.0},
      {.name = "torso_half_depth", .type = ParamType::Float, .default_value = std::to_string(torso.half_depth),
       .doc = "canonical torso: chest half-depth, m", .min = 0.05, .max = 1.0},
      {.name = "torso_centre_z", .type = ParamType::Float, .default_value = std::to_string(torso.centre_z),
       .doc = "canonical torso: chest centre z, m", .min = -1.0, .max = 1.0},
      {.name = "neck_height", .type = ParamType::Float, .default_value = std::to_string(torso.neck_height),
       .doc = "canonical torso: y of the neck points, m", .min = 0.5, .max = 2.5},
      {.name = "arm_angle", .type = ParamType::Float, .default_value = std::to_string(torso.arm_angle_deg),
       .doc = "canonical torso: arms below horizontal, deg", .min = 0.0, .max = 90.0},
  };
  d.create_garment = [](const Params& p) -> std::unique_ptr<GarmentSource> {
    tshirt::TshirtOptions o;
    if (p.get_string("size") == "auto")
      throw ConfigError("size auto is chosen for each body from its girth by drape simulate and drape generate (docs/garments.md, "
                        "\"Which size fits which body\"); here give a size: 3xsmall-xsmall, small, regular, large, xlarge or 2xlarge-6xlarge");
    o.grade = tshirt::size_grade(p.get_string("size"));
    o.target_vertices = parse_resolution(p.get_string("resolution"));
    o.print = p.get_bool("print");
    o.print_polygon = geometry::polygon_from_flat(p.get_float_list("print_polygon"), "print_polygon");
    o.torso.half_width = p.get_float("torso_half_width");
    o.torso.half_depth = p.get_float("torso_half_depth");
    o.torso.centre_z = p.get_float("torso_centre_z");
    o.torso.neck_height = p.get_float("neck_height");
    o.torso.arm_angle_deg = p.get_float("arm_angle");
    return std::make_unique<TshirtSource>(std::move(o));
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
