#pragma once
// MakeHuman clothes binding (.mhclo): each garment vertex is either one base-mesh
// vertex or a barycentric point of a base triangle plus an offset scaled by the
// body's current size along each axis. Fitting it to a morphed base mesh is how
// MakeHuman dresses any body.
#include <Eigen/Core>

#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace drape::makehuman {

struct ClothesBinding {
  std::string file;  // the .mhclo it was read from, for messages
  std::string name;
  std::string obj_file;
  struct Scale {
    int a = 0, b = 0;
    double reference = 1.0;
  };
  std::array<Scale, 3> scale{};  // x, y, z
  struct Ref {
    std::array<int, 3> vertex{};
    std::array<double, 3> weight{};
    Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  };
  std::vector<Ref> refs;  // one per garment .obj vertex, in .obj order
};

ClothesBinding read_mhclo(const std::filesystem::path& file);

// Garment vertex positions on a morphed base mesh (all vertices, helpers included).
Eigen::MatrixX3d fit_clothes(const ClothesBinding& binding, const Eigen::MatrixX3d& base);

}  // namespace drape::makehuman
