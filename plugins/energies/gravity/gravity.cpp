// Gravitational potential energy, the seed's L_g (eq. 6.16), written with the
// sign of a potential: E = -sum_v m(v) g^T x(v), so with g pointing down (-Y)
// E = sum_v m(v) |g| y(v) grows with height and minimising it lets cloth fall.
// Masses are lumped: each face's material-space area (UV in meters) times its
// material's density, a third to each corner. E is linear in x: the gradient is
// constant and the Hessian is zero (add_hessian appends nothing).
#include <drape/geometry/vertex_areas.hpp>
#include <drape/element_energy.hpp>
#include <drape/energy_input.hpp>
#include <drape/plugin.hpp>

namespace {

using namespace drape;

class Gravity final : public Energy {
 public:
  explicit Gravity(double g) : g_(g) {}

  void bind(const EnergyContext& context) override {
    // The checks every garment energy makes (UVs, materials, indices), written once.
    const Garment& garment = checked_garment(context);
    const double norm = context.gravity.norm();
    if (!(norm > 0.0)) throw ConfigError("the scene's gravity direction is zero");
    // The direction comes from the scene, the magnitude from the parameter `g`.
    force_per_kg_ = context.gravity / norm * g_;
    mass_ = geometry::vertex_masses(garment);
  }

  double value(const Eigen::MatrixX3d& x) const override {
    check(x);
    return -mass_.dot(x * force_per_kg_);
  }

  double add_gradient(const Eigen::MatrixX3d& x, Eigen::MatrixX3d& g) const override {
    check(x);
    g.noalias() -= mass_ * force_per_kg_.transpose();
    return value(x);
  }

  void add_hessian(const Eigen::MatrixX3d& x, Triplets&, bool) const override { check(x); }

  const Eigen::VectorXd& masses() const { return mass_; }

 private:
  void check(const Eigen::MatrixX3d& x) const { check_energy_input(x, mass_.size()); }
  double g_;
  Eigen::Vector3d force_per_kg_ = Eigen::Vector3d::Zero();
  Eigen::VectorXd mass_;
};

PluginList plugins() {
  PluginDescriptor d;
  d.kind = "energy";
  d.name = "gravity";
  d.doc = "Gravitational potential energy sum_v m(v) g y(v), lumped masses from material-space areas and densities.";
  d.params = {{.name = "g", .type = ParamType::Float, .default_value = "9.81",
               .doc = "gravitational acceleration in m/s^2 (direction from the scene, -Y)", .min = 0.0, .max = 1000.0}};
  d.create_energy = [](const Params& p) { return std::make_unique<Gravity>(p.get_float("g")); };
  return {d};
}

}  // namespace

DRAPE_PLUGIN_EXPORT(plugins)
