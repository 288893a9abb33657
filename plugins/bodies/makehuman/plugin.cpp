// Plugins over MakeHuman data (a folder laid out like ../shared/assets/makehuman):
//   body `makehuman`          sliders -> body mesh, BMI search over weight/muscle, posed by MakeHuman's rig
//   garment `makehuman_tshirt` the T-shirt of an outfit, dressed through its .mhclo
//   garment `makehuman_clothes` any piece of an outfit (index or group), the same way
#include "body_model.hpp"
#include "clothes.hpp"

#include <drape/bodies/body.hpp>
#include <drape/plugin.hpp>

#include <cstdlib>
#include <map>
#include <mutex>

namespace {

using namespace drape;
using namespace drape::makehuman;

// "" means $DRAPE_MAKEHUMAN_DIR, else the assets folder beside the source tree.
std::string resolve(const std::string& path) {
  if (!path.empty()) return path;
  if (const char* env = std::getenv("DRAPE_MAKEHUMAN_DIR")) return env;
  return DRAPE_DEFAULT_MAKEHUMAN_DIR;
}

// Loading the targets costs ~0.5 s: share one model per folder.
std::shared_ptr<const Model> model_for(const std::string& given) {
  const std::string path = resolve(given);
  static std::mutex mutex;
  static std::map<std::string, std::weak_ptr<const Model>> cache;
  std::lock_guard<std::mutex> lock(mutex);
  if (auto m = cache[path].lock()) return m;
  auto m = std::make_shared<const Model>(path);
  cache[path] = m;
  return m;
}

const char* kDefaultPath = "\"\"";

std::vector<ParamSpec> slider_params() {
  // The sliders of the MakeHuman body the .mhclo fits the garment to. A
  // simulation starts on the body model's mean shape (these defaults) and
  // morphs to the target, so the garment must be fitted to that body: keep
  // the defaults, for a women's outfit too (docs/garments.md).
  const std::string why = "; keep the default: the garment is fitted to the body a drape starts from, the mean shape";
  return {{.name = "gender", .type = ParamType::Float, .default_value = "1.0",
           .doc = "gender slider of the body the garment is fitted to (0 female, 1 male)" + why, .min = 0.0, .max = 1.0, .fits_start_body = true},
          {.name = "muscle", .type = ParamType::Float, .default_value = "0.5",
           .doc = "muscle slider of that body" + why, .min = 0.0, .max = 1.0, .fits_start_body = true},
          {.name = "weight", .type = ParamType::Float, .default_value = "0.5",
           .doc = "weight slider of that body" + why, .min = 0.0, .max = 1.0, .fits_start_body = true},
          {.name = "height", .type = ParamType::Float, .default_value = "0.5",
           .doc = "height slider of that body" + why, .min = 0.0, .max = 1.0, .fits_start_body = true},
          {.name = "proportions", .type = ParamType::Float, .default_value = "0.5",
           .doc = "proportions slider of that body" + why, .min = 0.0, .max = 1.0, .fits_start_body = true}};
}

class ClothesSource final : public GarmentSource {
 public:
  ClothesSource(std::shared_ptr<const Model> model, std::filesystem::path outfit, Sliders body, std::string piece)
      : model_(std::move(model)), outfit_(std::move(outfit)), body_(body), piece_(std::move(piece)) {}
  Garment build() const override { return load_clothes(*model_, outfit_, body_, piece_); }

 private:
  std::shared_ptr<const Model> model_;
  std::filesystem::path outfit_;
  Sliders body_;
  std::string piece_;
};

// The body sliders the garment is fitted to, and the outfit folder.
std::unique_ptr<GarmentSource> clothes_source(const Params& p, const std::string& piece) {
  Sliders s;
  s.gender = p.get_float("gender");
  s.muscle = p.get_float("muscle");
  s.weight = p.get_float("weight");
  s.height = p.get_float("height");
  s.proportions = p.get_float("proportions");
  const std::string root = resolve(p.get_string("path"));
  return std::make_unique<ClothesSource>(model_for(root), std::filesystem::path(root) / "clothes" / p.get_string("outfit"), s,
                                         piece);
}

PluginList plugins() {
  PluginDescriptor body;
  body.kind = "body";
  body.name = "makehuman";
  body.doc = "MakeHuman hm08 body (CC0 data folder): macro sliders, helpers removed, meters; BMI search over weight/muscle; "
             "posed by MakeHuman's own rig when the folder has rigs/default.mhskel and rigs/default_weights.mhw.";
  body.params = {{.name = "path", .type = ParamType::String, .default_value = kDefaultPath,
                  .doc = "MakeHuman data folder (base/base.obj, targets/macrodetails/, for poses rigs/); empty: $DRAPE_MAKEHUMAN_DIR or ../shared/assets/makehuman"},
                 {.name = "muscle", .type = ParamType::Float, .default_value = "-1",
                  .doc = "fixed muscle slider for the BMI search; -1 moves it with weight", .min = -1.0, .max = 1.0}};
  body.create_body = [](const Params& p) {
    return std::make_unique<MakeHumanBody>(model_for(p.get_string("path")), p.get_float("muscle"));
  };

  PluginDescriptor shirt;
  shirt.kind = "garment";
  shirt.name = "makehuman_tshirt";
  shirt.doc = "The T-shirt of a MakeHuman outfit (first piece of its .obj), fitted to a MakeHuman body by its .mhclo.";
  shirt.params = {{.name = "path", .type = ParamType::String, .default_value = kDefaultPath,
                   .doc = "MakeHuman data folder"},
                  {.name = "outfit", .type = ParamType::String, .default_value = "male_casualsuit04",
                   .doc = "outfit folder under clothes/"}};
  for (auto& s : slider_params()) shirt.params.push_back(s);
  shirt.create_garment = [](const Params& p) { return clothes_source(p, "0"); };

  PluginDescriptor clothes = shirt;
  clothes.name = "makehuman_clothes";
  clothes.doc = "Any piece of a MakeHuman outfit (by connected-piece index or OBJ group name), fitted to a MakeHuman body "
                "by the outfit's .mhclo so that it follows the body's shape.";
  clothes.params.push_back({.name = "piece", .type = ParamType::String, .default_value = "0",
                            .doc = "the piece: its index among the outfit .obj's connected pieces (numbered by first vertex: 0 "
                                   "the shirt, 1 the trousers in MakeHuman's suits) or the name of an OBJ group; several, "
                                   "comma-separated (\"0,1\": the whole suit), drape as one garment with a material "
                                   "region per piece (piece0, piece1, or the group's name) for the scene's materials"});
  clothes.create_garment = [](const Params& p) { return clothes_source(p, p.get_string("piece")); };
  return {body, shirt, clothes};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
