#pragma once
// A simulation scene (graphs/scenes/*.yaml, documented in docs/scenes.md): the
// body (model, its parameters and the shape to reach), the garment (template
// and its parameters), the material of each garment region, the effects --
// the energies to build, and nothing else -- and the solver settings.
//
//   base: tshirt.yaml          # optional: start from another scene, then override
//   body:    {model: parametric, params: {}, shape: {bmi: 35, height: 1.75, sex: 1}, pose: {elbow_flexion: 30}}
//   garment: {template: tshirt, params: {resolution: coarse}}
//   materials: {knit: gray-interlock, print: {base: screen-print, multipliers: {stretch: 100}}}
//   effects: [gravity, stretching, bending, collision]   # or a map name: {params}
//   solver:  {time_step: 0.1, morph_steps: 20, settle_steps: 40}
//
// Overrides in a derived scene replace single entries (a body parameter, one
// effect's parameters, one solver setting); `name: null` removes an effect or
// a material. Every value keeps the file and line it was written at.
#include <drape/errors.hpp>
#include <drape/params.hpp>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace drape {

class Registry;
class BodyModel;

struct SceneEffect {
  std::string name;  // an energy plugin
  ParamValues params;
  SourceLocation where;
};

struct SceneMaterial {
  std::string region;  // a region name of the garment template ("knit", "print")
  YAML::Node spec;     // a preset name, an ArcSim file (x.json, relative to `file`) or an inline preset (materials.hpp)
  std::string file;
  SourceLocation where;
};

struct Scene {
  std::string file;         // where it was read from ("<text>" for strings)
  std::string description;
  std::string body_model = "parametric";
  SourceLocation body_model_where;  // where `body: {model: ...}` was set (file only: the default)
  ParamValues body_params;  // the body plugin's parameters
  ParamValues shape;        // bmi, height, sex: the body the garment is draped on
  // Joint angles by name, degrees (`body: {pose: {shoulder_abduction: 20}}`,
  // docs/poses.md): the target body is posed; empty: the A-pose.
  ParamValues pose;
  std::string garment = "tshirt";
  SourceLocation garment_where;  // where `garment: {template: ...}` was set (file only: the default)
  ParamValues garment_params;
  double garment_grade = 1.0;  // the garment graded by this factor (garment_grading.hpp; `garment: {grade: g}`)
  // `garment: {grade: auto}`: each body gets the grade that gives it the
  // garment's design ease (drape/scene/auto_grade.hpp); garment_grade is then 1.
  bool garment_grade_auto = false;
  std::vector<SceneMaterial> materials;
  // Materials a derived scene's `region: null` took away from its base: the
  // region then wears the garment's own, which a simulation says (where =
  // the null's line; an outside check's `knit:` left empty swapped a linear
  // knit for a 23 times stiffer one without a word).
  std::vector<SceneMaterial> dropped_materials;
  std::vector<SceneEffect> effects;
  ParamValues solver;

  bool has_effect(const std::string& name) const;
  // The resolved scene as YAML (no `base:`): what datasets store.
  std::string yaml() const;
};

// Reads a scene file, following `base:` chains (relative to the file).
// ConfigError with file:line for unknown keys (with close matches), bad
// values and loops in the chain.
Scene load_scene(const std::filesystem::path& file);
Scene parse_scene(const std::string& text, const std::string& name_for_errors = "<scene>");

// The settings the solver section accepts, with defaults and ranges.
const std::vector<ParamSpec>& scene_solver_specs();
const std::vector<ParamSpec>& scene_shape_specs();

// Checks names against the registry: every effect is an energy plugin (the
// known ones listed when not), the body and garment plugins exist, and every
// plugin's parameters are valid. Throws ConfigError at the scene's line.
void validate_scene(const Scene& scene, const Registry& registry);

// The scene's body model, made by its plugin with the scene's parameters
// (what a Simulation drapes on; drape optimize asks it for its rig's vertex
// count before choosing a model).
std::unique_ptr<BodyModel> make_scene_body_model(const Registry& registry, const Scene& scene);

}  // namespace drape
