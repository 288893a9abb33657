#include "mhclo.hpp"

#include <drape/errors.hpp>

#include <algorithm>
#include <fstream>
#include <sstream>

namespace drape::makehuman {

ClothesBinding read_mhclo(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw ConfigError("cannot read MakeHuman clothes binding '" + file.string() + "'");
  ClothesBinding b;
  b.file = file.string();
  std::string line;
  int line_no = 0;
  bool in_verts = false;
  auto fail = [&](const std::string& what) { throw ConfigError(SourceLocation{file.string(), line_no}, what); };
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    std::string key;
    ss >> key;
    if (in_verts) {
      // A vertex line starts with a number; anything else ends the section.
      if (!key.empty() && (std::isdigit(static_cast<unsigned char>(key[0])) != 0)) {
        std::vector<double> v{std::stod(key)};
        double x;
        while (ss >> x) v.push_back(x);
        ClothesBinding::Ref r;
        if (v.size() == 1) {
          r.vertex = {static_cast<int>(v[0]), static_cast<int>(v[0]), static_cast<int>(v[0])};
          r.weight = {1.0, 0.0, 0.0};
        } else if (v.size() == 9) {
          r.vertex = {static_cast<int>(v[0]), static_cast<int>(v[1]), static_cast<int>(v[2])};
          r.weight = {v[3], v[4], v[5]};
          r.offset = {v[6], v[7], v[8]};
        } else {
          fail("a vertex line needs 1 or 9 numbers, found " + std::to_string(v.size()));
        }
        b.refs.push_back(r);
        continue;
      }
      in_verts = false;
    }
    if (key == "name") ss >> b.name;
    else if (key == "obj_file") ss >> b.obj_file;
    else if (key == "x_scale" || key == "y_scale" || key == "z_scale") {
      ClothesBinding::Scale& s = b.scale[static_cast<std::size_t>(key[0] - 'x')];
      if (!(ss >> s.a >> s.b >> s.reference) || s.reference == 0.0) fail("bad " + key + " line");
    } else if (key == "verts") {
      in_verts = true;
    }
  }
  if (b.refs.empty()) throw ConfigError(file.string() + ": no `verts` section");
  return b;
}

Eigen::MatrixX3d fit_clothes(const ClothesBinding& b, const Eigen::MatrixX3d& base) {
  Eigen::Vector3d scale;
  for (int axis = 0; axis < 3; ++axis) {
    const auto& s = b.scale[static_cast<std::size_t>(axis)];
    if (s.a >= base.rows() || s.b >= base.rows())
      throw ConfigError(b.file + ": a scale reference names base vertex " + std::to_string(std::max(s.a, s.b)) +
                        ", but the base mesh has " + std::to_string(base.rows()) + " vertices: a binding for another base mesh");
    scale[axis] = std::abs(base(s.a, axis) - base(s.b, axis)) / s.reference;
  }
  Eigen::MatrixX3d out(static_cast<Eigen::Index>(b.refs.size()), 3);
  for (std::size_t i = 0; i < b.refs.size(); ++i) {
    const auto& r = b.refs[i];
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      if (r.vertex[k] < 0 || r.vertex[k] >= base.rows())
        throw ConfigError(b.file + ": garment vertex " + std::to_string(i) + " is bound to base vertex " +
                          std::to_string(r.vertex[k]) + ", but the base mesh has " + std::to_string(base.rows()) +
                          " vertices: a binding for another base mesh");
      p += r.weight[k] * base.row(r.vertex[k]).transpose();
    }
    out.row(static_cast<Eigen::Index>(i)) = p + r.offset.cwiseProduct(scale);
  }
  return out;
}

}  // namespace drape::makehuman
