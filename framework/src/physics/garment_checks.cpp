// The garment checks shared by every energy over a garment's faces.
#include <drape/element_energy.hpp>
#include <drape/error_context.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace drape {

const Garment& checked_garment(const EnergyContext& context) {
  if (!context.garment) throw ConfigError("no garment is bound");
  const Garment& garment = *context.garment;
  const Mesh& mesh = garment.mesh;
  if (!mesh.has_uv())
    throw ConfigError("the garment has no material-space UVs (uv and uv_faces), so its rest shape is unknown");
  if (garment.materials.empty()) throw ConfigError("the garment has no materials");
  if (garment.face_material.size() && garment.face_material.size() != mesh.num_faces())
    throw ConfigError("the garment has " + std::to_string(garment.face_material.size()) + " face materials for " +
                      std::to_string(mesh.num_faces()) + " faces");
  if (!mesh.uv.allFinite()) throw ConfigError("the garment's UVs are not all finite");
  const int nv = mesh.num_vertices(), nuv = static_cast<int>(mesh.uv.rows());
  const int materials = static_cast<int>(garment.materials.size());
  for (int f = 0; f < mesh.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k)
      if (mesh.faces(f, k) < 0 || mesh.faces(f, k) >= nv || mesh.uv_faces(f, k) < 0 || mesh.uv_faces(f, k) >= nuv)
        throw ConfigError("face " + std::to_string(f) + " has a vertex or UV index out of range");
    const int m = garment.material_of(f);
    if (m < 0 || m >= materials)
      throw ConfigError("face " + std::to_string(f) + " names material " + std::to_string(m) + " of " +
                        std::to_string(materials));
  }
  for (const Material& m : garment.materials) {
    bool finite = m.model == Material::Model::Linear ? m.stretch.allFinite() && std::isfinite(m.bending) : true;
    if (m.model == Material::Model::Arcsim) {
      for (const Eigen::Vector4d& row : m.arcsim.stretching) finite = finite && row.allFinite();
      for (const auto& row : m.arcsim.bending)
        for (const double b : row) finite = finite && std::isfinite(b);
    }
    if (!finite) throw ConfigError("material '" + m.name + "' has a non-finite stiffness");
  }
  return garment;
}

const Garment& checked_garment(const EnergyContext& context, const std::string& energy) {
  return in_context(energy, [&]() -> const Garment& { return checked_garment(context); });
}

}  // namespace drape
