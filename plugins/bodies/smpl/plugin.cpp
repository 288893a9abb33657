// body `smpl`: an SMPL model converted to HDF5 (see docs/smpl.md).
#include "smpl_model.hpp"

#include <drape/bodies/body.hpp>
#include <drape/plugin.hpp>

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
              {.name = "betas", .type = ParamType::Int, .default_value = "10",
               .doc = "how many shape coefficients to use", .min = 1.0, .max = 300.0}};
  d.create_body = [](const Params& p) {
    return std::make_unique<smpl::SmplBody>(smpl::read_smpl_h5(p.get_string("file")), static_cast<int>(p.get_int("betas")));
  };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
