#pragma once
// A cloth material in physical units (what a garment's regions are made of),
// and ArcSim's measured tables it may carry. The energies read it
// (energy.hpp's Garment); materials/ reads the presets and files into it.
#include <Eigen/Core>

#include <array>
#include <string>

namespace drape {

// ArcSim's measured cloth data (Wang, Ramamoorthi & O'Brien 2011, "Data-driven
// elastic models for cloth"), laid out as ArcSim's materials/*.json files hold
// it, after any multipliers. How the energies use it: docs/materials.md and
// drape/physics/arcsim_material.hpp.
struct ArcsimData {
  // stretching[0]: [k_uu, k_uv, k_vv, k_shear] (N/m) at zero strain;
  // stretching[1 + i]: the same at a principal stretch of 1 + 1/6 whose
  // direction is i * 22.5 degrees from u (i = 0..4: 0, 22.5, 45, 67.5, 90).
  std::array<Eigen::Vector4d, 6> stretching{};
  // bending[b][j] (N*m): edge direction b * 45 degrees from u (b = 0, 1, 2),
  // curvature j * 10 1/m (j = 0..4).
  std::array<std::array<double, 5>, 3> bending{};
};

// A cloth material in physical units.
struct Material {
  // Linear: constant stiffness (stretch, bending), drape's model before
  // ArcSim's tables; Arcsim: stiffness from `arcsim` as ArcSim evaluates it.
  enum class Model { Linear, Arcsim };
  std::string name;
  Model model = Model::Linear;
  double density = 0.187;  // kg/m^2
  // Linear model: ArcSim-style stretching coefficients [k_uu, k_uv(coupling), k_vv, k_shear] in N/m.
  Eigen::Vector4d stretch{16.6, -14.7, 34.5, 36.9};
  double bending = 1e-5;   // N*m, linear model
  double thickness = 4.7e-4;  // m
  ArcsimData arcsim;       // Arcsim model
};

}  // namespace drape
