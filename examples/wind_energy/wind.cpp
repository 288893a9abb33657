// A uniform wind load on the garment, as an out-of-tree example of an energy:
//
//   E(x) = -sum_v a(v) * w . x(v),   a(v) = pressure * (lumped material-space area of v)
//
// where w is the unit wind direction and the lumped area gives each vertex a
// third of the UV (material-space, square meters) area of every face around it.
// The force -dE/dx = a(v) w is the same everywhere on the cloth per unit of
// material area, so stretching the garment does not change the total load.
// E is linear in x: the gradient is constant and the Hessian is zero.
#include <drape/energy.hpp>
#include <drape/energy_input.hpp>
#include <drape/plugin.hpp>

#include <cmath>

namespace {

using namespace drape;

class WindEnergy final : public Energy {
 public:
  WindEnergy(const Eigen::Vector3d& direction, double pressure) : direction_(direction), pressure_(pressure) {}

  void bind(const EnergyContext& context) override {
    if (!context.garment) throw ConfigError("bind() needs a garment");
    const Mesh& mesh = context.garment->mesh;
    if (!mesh.has_uv())
      throw ConfigError("the garment has no material-space UV layout (uv and uv_faces), which gives the cloth area");
    load_.setZero(mesh.num_vertices());
    for (int f = 0; f < mesh.num_faces(); ++f) {
      const Eigen::Vector2d a = mesh.uv.row(mesh.uv_faces(f, 0));
      const Eigen::Vector2d b = mesh.uv.row(mesh.uv_faces(f, 1));
      const Eigen::Vector2d c = mesh.uv.row(mesh.uv_faces(f, 2));
      const Eigen::Vector2d e1 = b - a, e2 = c - a;
      // Unsigned: a mirrored UV island is still cloth.
      const double area = 0.5 * std::abs(e1.x() * e2.y() - e1.y() * e2.x());
      for (int k = 0; k < 3; ++k) load_[mesh.faces(f, k)] += pressure_ * area / 3.0;
    }
  }

  double value(const Eigen::MatrixX3d& x) const override {
    check(x);
    return -load_.dot(x * direction_);
  }

  double add_gradient(const Eigen::MatrixX3d& x, Eigen::MatrixX3d& g) const override {
    check(x);
    g.noalias() -= load_ * direction_.transpose();
    return value(x);
  }

  // Linear energy: the Hessian is zero, there is nothing to append.
  void add_hessian(const Eigen::MatrixX3d& x, Triplets&, bool) const override { check(x); }

 private:
  // The vertex count bind() saw, and every coordinate finite (energy_input.hpp).
  void check(const Eigen::MatrixX3d& x) const { check_energy_input(x, load_.size()); }

  Eigen::Vector3d direction_;  // unit
  double pressure_;            // Pa = N / m^2
  Eigen::VectorXd load_;       // [V] pressure * lumped area, N
};

std::unique_ptr<Energy> create(const Params& params) {
  const std::vector<double> d = params.get_float_list("direction");
  if (d.size() != 3)
    throw ConfigError("parameter 'direction' needs 3 numbers [x, y, z], got " + std::to_string(d.size()));
  const Eigen::Vector3d w(d[0], d[1], d[2]);
  if (!(w.norm() > 0.0) || !std::isfinite(w.norm()))
    throw ConfigError("parameter 'direction' must be a finite non-zero vector");
  return std::make_unique<WindEnergy>(w.normalized(), params.get_float("pressure"));
}

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "energy";
  d.name = "wind";
  d.doc = "Uniform wind load: E = -sum_v pressure * uv_area(v) * w.x(v) (example out-of-tree plugin).";
  d.params = {
      {.name = "direction", .type = ParamType::FloatList, .default_value = "[0, 0, 1]",
       .doc = "wind direction [x, y, z] (normalised; Y is up)"},
      {.name = "pressure", .type = ParamType::Float, .default_value = "1.0",
       .doc = "force per material area in Pa (N/m^2)", .min = 0.0},
  };
  d.create_energy = create;
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
