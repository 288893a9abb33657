// `drape bench contact`: what each contact costs per call on one core, the
// barrier (IPC, never crossing) beside the penalty (`collision`): value (with
// the barrier's pair search), gradient, Hessian, and the barrier's continuous
// collision bound for a move 95 % of the way to the body (additive CCD stops,
// conservatively, before a pair is down to a tenth of its distance); and the
// independent surface-crossing count. The scene is a cloth shell (an icosphere, its own
// rest shape) at least `--gap` outside a sphere body: every vertex, face and edge of
// the cloth in contact range, the barrier's worst case per vertex.
#include "bench.hpp"

#include <drape/energy.hpp>
#include <drape/geometry/closed_shapes.hpp>
#include <drape/geometry/closest_point.hpp>
#include <drape/geometry/surface_crossings.hpp>
#include <drape/registry.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <vector>

namespace drape::cli {
namespace DRAPE_UNITY_ID {  // the anonymous namespace, or a unique one in a unity build (command.hpp)

using Clock = std::chrono::steady_clock;

// Best and median of `repeats` timed calls, in ms.
BestAndMedian time_ms(int repeats, const std::function<void()>& call) {
  std::vector<double> ms;
  for (int k = 0; k < repeats; ++k) {
    const auto t = Clock::now();
    call();
    ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t).count());
  }
  return best_and_median(ms);
}

// The icosphere as a garment whose material space is its own shape: each
// face laid flat with its 3D edge lengths.
Garment shell_garment(const Mesh& shell) {
  Garment g;
  g.mesh = shell;
  g.mesh.uv.resize(3 * shell.faces.rows(), 2);
  g.mesh.uv_faces.resize(shell.faces.rows(), 3);
  for (int f = 0; f < shell.faces.rows(); ++f) {
    const Eigen::Vector3d a = shell.vertices.row(shell.faces(f, 0)), b = shell.vertices.row(shell.faces(f, 1)),
                          c = shell.vertices.row(shell.faces(f, 2));
    const double ab = (b - a).norm(), t = (c - a).dot(b - a) / ab, h = ((c - a) - t * (b - a) / ab).norm();
    g.mesh.uv.row(3 * f) << 0, 0;
    g.mesh.uv.row(3 * f + 1) << ab, 0;
    g.mesh.uv.row(3 * f + 2) << t, h;
    g.mesh.uv_faces.row(f) << 3 * f, 3 * f + 1, 3 * f + 2;
  }
  g.materials.push_back(Material{});
  return g;
}

int run(const std::vector<std::string>& args) {
  po::options_description opts("drape bench contact");
  opts.add_options()("garment-level", po::value<int>()->default_value(4), "icosphere level of the cloth shell (4: 2,562 vertices)")(
      "body-level", po::value<int>()->default_value(5), "icosphere level of the sphere body (5: 10,242 vertices)")(
      "gap", po::value<double>()->default_value(7e-4), "m between the shell and the body (barrier d_hat: 1 mm)")(
      "repeats", po::value<int>()->default_value(5), "timed calls of each (best and median shown)");
  po::variables_map vm;
  if (!parse("drape bench contact [--garment-level 4] [--body-level 5] [--gap 0.0007]", args, opts, {}, vm)) return 0;
  const double radius = 0.1, gap = vm["gap"].as<double>();
  if (!(gap > 0)) throw UsageError("--gap must be > 0");
  const int repeats = vm["repeats"].as<int>();
  if (repeats < 1) throw UsageError("--repeats " + std::to_string(repeats) + ": expected at least 1");
  for (const char* level : {"garment-level", "body-level"})
    if (const int l = vm[level].as<int>(); l < 0 || l > 8)
      throw UsageError(std::string("--") + level + " " + std::to_string(l) + ": expected an icosphere level 0 to 8");
  Registry& registry = Registry::load_default(plugin_path(vm));
  const geometry::BodySurface body(geometry::icosphere(vm["body-level"].as<int>(), radius));
  // The shell's flat faces sag inside its vertices' sphere: it is scaled so
  // that its deepest face centre is `gap` outside the body's vertex sphere.
  Mesh shell = geometry::icosphere(vm["garment-level"].as<int>(), 1.0);
  double deepest = 1;
  for (int f = 0; f < shell.num_faces(); ++f)
    deepest = std::min(deepest, ((shell.vertices.row(shell.faces(f, 0)) + shell.vertices.row(shell.faces(f, 1)) +
                                  shell.vertices.row(shell.faces(f, 2))) / 3).norm());
  shell.vertices *= (radius + gap) / deepest;
  const Garment garment = shell_garment(shell);
  EnergyContext context;
  context.garment = &garment;
  context.body = &body;
  const Eigen::MatrixX3d x = garment.mesh.vertices;
  // Each vertex 95 % of the way to the body's vertex sphere.
  Eigen::MatrixX3d inward(x.rows(), 3);
  for (Eigen::Index v = 0; v < x.rows(); ++v) inward.row(v) = -0.95 * (x.row(v).norm() - radius) * x.row(v).normalized();

  std::printf("## Contact cost per call on one core: a cloth shell %.1f mm outside a sphere body\n\n", 1000 * gap);
  std::printf("garment %d vertices, %d faces; body %d vertices, %d faces; best (median) of %d calls, ms\n\n",
              garment.mesh.num_vertices(), garment.mesh.num_faces(), static_cast<int>(body.vertices().rows()),
              static_cast<int>(body.faces().rows()), repeats);
  std::printf("| contact | value | gradient | Hessian | step bound (CCD) |\n|---|---|---|---|---|\n");
  for (const char* name : {"barrier", "collision"}) {
    auto energy = registry.create_energy(name, Params(registry.get(name).params, {}, name));
    energy->bind(context);
    // A fresh x for every value call, so the barrier searches its pairs anew
    // (the gradient and Hessian then reuse them, as in a Newton iteration).
    Eigen::MatrixX3d y = x;
    const BestAndMedian value = time_ms(repeats, [&] {
      y(0, 0) += 1e-12;
      energy->value(y);
    });
    Eigen::MatrixX3d g = Eigen::MatrixX3d::Zero(x.rows(), 3);
    const BestAndMedian gradient = time_ms(repeats, [&] { energy->add_gradient(y, g); });
    const BestAndMedian hessian = time_ms(repeats, [&] {
      Triplets h;
      energy->add_hessian_lower(y, h, true);
    });
    double alpha = 1;
    const BestAndMedian bound = time_ms(repeats, [&] { alpha = energy->max_step(y, inward); });
    std::printf("| %s | %.2f (%.2f) | %.2f (%.2f) | %.2f (%.2f) | %.2f (%.2f), alpha %.3f |\n", name, value.best,
                value.median, gradient.best, gradient.median, hessian.best, hessian.median, bound.best, bound.median, alpha);
  }
  const BestAndMedian crossings =
      time_ms(repeats, [&] { geometry::surface_crossings(x, garment.mesh.faces, body.vertices(), body.faces()); });
  std::printf("\nsurface crossing count (independent of both contacts): %.2f (%.2f) ms\n", crossings.best, crossings.median);
  return 0;
}

const RegisterBench registration{
    {"contact", "ms per value, gradient, Hessian and CCD bound of the barrier and penalty contacts", run}};

}  // namespace
}  // namespace drape::cli
