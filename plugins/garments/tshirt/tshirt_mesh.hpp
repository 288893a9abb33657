#pragma once
// Builds the T-shirt garment: meshes both panels, sews them along the seams
// (seam vertices shared, two UVs each), places the result around the canonical
// torso (of the size's fit body: fit_torso) and assigns materials.
#include "pattern.hpp"
#include "placement.hpp"

#include <drape/energy.hpp>

namespace drape::tshirt {

struct TshirtOptions {
  double grade = 1.0;            // the size's chest over the regular's (PatternSpec::graded; same topology)
  int target_vertices = 3500;
  TorsoFrame torso;
  bool print = false;
  Polygon2 print_polygon;        // front panel's normalised [0,1]^2 coordinates
};

struct TshirtResult {
  Garment garment;
  Eigen::VectorXi panel_of_face;  // 0 front, 1 back
  double min_uv_angle_deg = 0;
  double spacing = 0;             // lattice step of the regular pattern, m
};

TshirtResult build_tshirt(const TshirtOptions& options);

}  // namespace drape::tshirt
