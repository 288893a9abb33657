#pragma once
// An energy a plugin made, as the registry hands it out: every call goes to
// the plugin's energy, and every drape error it throws comes back with the
// plugin's name in front (error_context.hpp), so the plugin writes none.
#include <drape/energy.hpp>

#include <memory>
#include <string>

namespace drape {

class PluginEnergy final : public Energy {
 public:
  PluginEnergy(std::string name, std::unique_ptr<Energy> energy);

  void bind(const EnergyContext& context) override;
  double value(const Eigen::MatrixX3d& x) const override;
  double add_gradient(const Eigen::MatrixX3d& x, Eigen::MatrixX3d& g) const override;
  void add_hessian(const Eigen::MatrixX3d& x, Triplets& h, bool project_psd = true) const override;
  void add_hessian_lower(const Eigen::MatrixX3d& x, Triplets& h, bool project_psd = true) const override;
  bool needs_body() const override { return energy_->needs_body(); }
  bool has_kinks() const override { return energy_->has_kinks(); }
  double max_step(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& dx, const Eigen::MatrixX3d* body_from = nullptr,
                  const Eigen::MatrixX3d* body_to = nullptr) const override;
  bool bounds_steps() const override { return energy_->bounds_steps(); }
  double activation_distance() const override { return energy_->activation_distance(); }
  void vertex_gradient_samples(const Eigen::MatrixX3d& x, int vertex, double radius,
                               std::vector<Eigen::Vector3d>& samples) const override;
  Dissipation* dissipation() override { return energy_->dissipation(); }

 private:
  std::string name_;
  std::unique_ptr<Energy> energy_;
};

}  // namespace drape
