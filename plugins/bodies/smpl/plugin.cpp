// body `smpl`: an SMPL model converted to HDF5 (see docs/smpl.md).
#include "smpl_model.hpp"

#include <drape/bodies/body.hpp>
#include <drape/plugin.hpp>

#include <algorithm>
#include <utility>

namespace {

drape::PluginList plugins() {
  using namespace drape;
  PluginDescriptor d;
  d.kind = "body";
  d.name = "smpl";
  d.doc = "SMPL body (licence required) from an HDF5 conversion: v_template, shapedirs, f, and for poses by SMPL's theta "
          "J_regressor, weights, kintree_table, posedirs; BMI along the volume direction.";
  d.params = {{.name = "file", .type = ParamType::String, .default_value = "smpl_neutral.h5",
               .doc = "the converted model (docs/smpl.md)"},
              {.name = "betas", .type = ParamType::Int, .default_value = "0",
               .doc = "how many shape coefficients to use, at most the file's /shapedirs count (0: all of them up to 10, "
                      "SMPL's own count)",
               .min = 0.0, .max = 300.0}};
  d.create_body = [](const Params& p) {
    smpl::SmplData data = smpl::read_smpl_h5(p.get_string("file"));
    const auto asked = static_cast<int>(p.get_int("betas"));
    const int betas = asked > 0 ? asked : std::min<int>(10, static_cast<int>(data.shapedirs.cols()));
    return std::make_unique<smpl::SmplBody>(std::move(data), betas);
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
