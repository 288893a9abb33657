#pragma once
// Checks and value readers shared by parsing a preset, reading an ArcSim file
// and resolving a preset (framework-internal). Every error is a ConfigError at
// the file:line of the value at fault, naming the field.
#include <drape/errors.hpp>
#include <drape/materials/materials.hpp>

#include <yaml-cpp/yaml.h>

#include <Eigen/Core>

#include <array>
#include <filesystem>
#include <string>

namespace drape::materials_detail {

// An ArcSim file sets no thickness (ArcSim's data-driven materials have none);
// drape uses SNUG's 0.47 mm, as for its linear presets (docs/materials.md).
inline constexpr double kDefaultArcsimThickness = 4.7e-4;  // m

// "material 'name'" or "inline material".
std::string owner_of(const std::string& preset_name);

// Beyond these a value is not a cloth's (nor a sheet's) but a typo or a unit
// mistake, and it would only surface later as a drape that "does not fit":
// ArcSim's materials span 0.07-0.32 kg/m^2, 170-1.8e6 N/m and up to 4e-4 N*m;
// a 1 mm steel sheet is 7.8 kg/m^2, 2e8 N/m and 17 N*m.
inline constexpr double kMaxDensity = 100;     // kg/m^2
inline constexpr double kMinDensity = 1e-4;    // kg/m^2: 200 times lighter than chiffon (about 0.02)
inline constexpr double kMaxStretch = 1e9;     // N/m, any stretching coefficient's magnitude
inline constexpr double kMaxBending = 1e3;     // N*m
inline constexpr double kMaxMultiplier = 1e6;  // a `multipliers` factor (the shipped print is 100x stiffer)
// ConfigError at n unless |v| <= limit, naming the key, the unit and the limit.
void check_cloth_range(double v, double limit, const std::string& file, const YAML::Node& n, const std::string& owner,
                       const std::string& key, const char* unit);

// A finite number ("`key` must be a number, got 'x'" otherwise).
double number(const std::string& file, const YAML::Node& n, const std::string& owner, const std::string& key);
// The same, > 0; `unit` is shown in the message.
double positive(const std::string& file, const YAML::Node& n, const std::string& owner, const std::string& key,
                const char* unit);

// ConfigError at `where` unless the stretch coefficients give a positive
// definite membrane energy: k_uu > 0, k_vv > 0, k_uu k_vv > k_uv^2 (the 2x2
// block on the normal strains) and k_shear > 0. Otherwise some strain would have
// zero or negative energy and the cloth could stretch for free.
void check_stretch(const Eigen::Vector4d& k, const SourceLocation& where, const std::string& owner);

// ArcSim's `stretching` table: exactly 6 rows of exactly 4 finite numbers
// (N/m); row 0 must pass check_zero_strain_row. Any sign elsewhere: the
// measured tables have negative entries, which ArcSim clamps to zero.
std::array<Eigen::Vector4d, 6> stretching_table(const std::string& file, const YAML::Node& n, const std::string& owner);
// ArcSim's `bending` table: exactly 3 rows of exactly 5 finite numbers >= 0 (N*m).
std::array<std::array<double, 5>, 3> bending_table(const std::string& file, const YAML::Node& n, const std::string& owner);

// ArcSim clamps every interpolated coefficient below zero to zero; at zero
// strain it uses row 0 as it is, so k_uu <= 0 or k_vv <= 0 there leaves the
// cloth without stiffness along u or v at rest. ConfigError at `where` then.
void check_zero_strain_row(const Eigen::Vector4d& row, const SourceLocation& where, const std::string& owner);

// `path` as named in `naming_file`: relative paths are relative to its folder.
std::filesystem::path relative_to(const std::string& naming_file, const std::string& path);

// True for a material spec that is a string naming an ArcSim file (ends in .json).
bool names_arcsim_file(const std::string& spec);

// The map of an ArcSim material file (`file` names it) as a complete
// model-arcsim preset named `name`; see read_arcsim_file.
MaterialPreset parse_arcsim_file_body(const std::string& name, const YAML::Node& body, const std::string& file);

// The material of a preset without a base (every field its own, or its
// file's); checked as resolve_preset checks it. Named after p.name, else its
// file's stem, else "inline".
Material complete_material(const MaterialPreset& p);

// Reads the ArcSim material file at `path` (named at `named_at`) as a complete
// model-arcsim preset named `name`: comments blanked, then parsed as a preset
// that may hold only doc, model (arcsim), density, stretching, bending and
// thickness. An unreadable file is a ConfigError at `named_at` with the path.
MaterialPreset read_arcsim_file(const std::filesystem::path& path, const std::string& name, const SourceLocation& named_at);

}  // namespace drape::materials_detail
