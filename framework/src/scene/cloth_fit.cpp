// The garment's cloth around a body, in words (cloth_fit.hpp).
#include "cloth_fit.hpp"

#include <drape/materials/materials.hpp>
#include <drape/scene/garment_size.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace drape::scene_detail {
namespace {

// A material's stretching stiffness at rest (N/m): the larger of its warp
// and weft coefficients, as ArcSim's tables and drape's linear model give them.
double stretch_stiffness(const Material& m) {
  const Eigen::Vector4d& k = m.model == Material::Model::Arcsim ? m.arcsim.stretching[0] : m.stretch;
  return std::max(std::abs(k[0]), std::abs(k[2]));
}

}  // namespace

std::string cloth_too_short(double loop, const Eigen::MatrixX3d& start_body, const Eigen::MatrixX3i& body_faces,
                            const PatternSource& pattern) {
  const double ease = garment_ease(loop, start_body, body_faces);  // NaN when either is not measured
  const double around = loop / (1.0 + ease);
  if (!std::isfinite(ease) || around / loop - 1.0 <= kMaxStartStretch) return "";
  char text[700];
  std::snprintf(text, sizeof text,
                "the garment's cloth is %.1f %% shorter around than the body it is put on before the body morphs (its "
                "narrowest loop over the chest band measures %.3f m at rest, in its material space; the body's chest or "
                "belly %.3f m): it would start stretched by %.1f %% around, more than the %.0f %% a garment is put on "
                "with, so it cannot be put on; ",
                -100.0 * ease, loop, around, 100.0 * (around / loop - 1.0), 100.0 * kMaxStartStretch);
  std::string out = text;
  if (pattern.grade < 1.0) {
    // A grade below the design size cut it short (an outside check's
    // grade 0.5 was told its pattern was too small and a grade would not
    // help): the grade that puts it on, rounded up in its second decimal.
    const double wanted = pattern.grade * around / (loop * (1.0 + kMaxStartStretch));
    std::snprintf(text, sizeof text,
                  "the scene's garment: {grade: %.3g} cuts its cloth that small: grade %.2f or more puts it on this "
                  "body (1 is its design size)",
                  pattern.grade, std::ceil(wanted * 100.0 - 1e-9) / 100.0);
    return out + text;
  }
  if (pattern.has_uv_scale && !pattern.from_shape) {
    // The uv_scale whose cloth is as long around as the body, rounded up in its second digit.
    const double wanted = pattern.uv_scale * around / loop;
    const double step = std::pow(10.0, std::floor(std::log10(wanted)) - 1);
    std::snprintf(text, sizeof text,
                  "garment: {params: {uv_scale: %.3g}} makes its cloth as long around as the body (its UVs times "
                  "uv_scale are its pattern in metres)",
                  std::ceil(wanted / step - 1e-9) * step);
    return out + text;
  }
  if (pattern.from_shape)
    return out + "its shape, laid flat, is its cloth (material_space: rest): model it around the body model's mean "
                 "body (drape body writes it), not inside it";
  return out + "its pattern is cut smaller than the body (a grade does not change that: a graded garment is put on a "
               "body graded alike)";
}

std::string shape_larger_than_cloth(double cloth, double shape_loop, const PatternSource& pattern) {
  if (!std::isfinite(cloth) || !std::isfinite(shape_loop) || !(cloth > 0) || shape_loop / cloth - 1.0 <= kMaxStartStretch)
    return "";
  char text[600];
  std::snprintf(text, sizeof text,
                "the garment is modelled %.0f %% longer around than its cloth (its narrowest loop over the chest band "
                "%.3f m as modelled, %.3f m at rest in its material space): it starts stretched by that much and pulls "
                "in as it settles; its fit is told by its cloth",
                100.0 * (shape_loop / cloth - 1.0), shape_loop, cloth);
  std::string out = text;
  if (pattern.has_uv_scale && !pattern.from_shape) {
    std::snprintf(text, sizeof text, " (garment: {params: {uv_scale: %.3g}} makes the cloth the size of the shape)",
                  pattern.uv_scale * shape_loop / cloth);
    out += text;
  }
  return out;
}

std::string cloth_far_longer_than_shape(double cloth, double shape_loop, const PatternSource& pattern) {
  if (!std::isfinite(cloth) || !std::isfinite(shape_loop) || !(shape_loop > 0) || cloth / shape_loop <= kMaxClothOverShape)
    return "";
  char text[600];
  std::snprintf(text, sizeof text,
                "the garment's cloth is %.3g times as long around as the garment as modelled (its narrowest loop over "
                "the chest band %.3f m at rest in its material space, %.3f m as modelled): its pattern is likely in "
                "another unit than metres",
                cloth / shape_loop, cloth, shape_loop);
  std::string out = text;
  if (pattern.has_uv_scale && !pattern.from_shape) {
    // A power of ten when it is within a tenth of one (UVs in centimetres: 0.01, not 0.00998).
    const double exact = pattern.uv_scale * shape_loop / cloth;
    const double ten = std::pow(10.0, std::round(std::log10(exact)));
    std::snprintf(text, sizeof text, "; garment: {params: {uv_scale: %.3g}} makes the cloth the size of the shape",
                  std::abs(exact / ten - 1.0) < 0.1 ? ten : exact);
    out += text;
  }
  return out;
}

std::vector<std::string> slow_solver_settings(const SolverSettings& solver, const std::function<std::string(int)>& newton) {
  std::vector<std::string> out;
  const SolverSettings defaults;
  if (solver.time_step < 0.1 * defaults.time_step) {
    char text[160];
    std::snprintf(text, sizeof text, "the time step %.3g s (the default %.3g s) moves the cloth only so far a step",
                  solver.time_step, defaults.time_step);
    out.emplace_back(text);
  }
  if (solver.max_newton_iterations < kFewNewtonIterations) out.push_back(newton(solver.max_newton_iterations));
  return out;
}

std::string why_morph_blocked(const MorphBlocked& blocked, int morph_steps, const Garment& garment, double loop,
                              const Eigen::MatrixX3d& body_now, const Eigen::MatrixX3i& body_faces,
                              const SolverSettings& solver, bool sized, const std::vector<std::string>& effect_notes) {
  char text[900];
  std::snprintf(text, sizeof text,
                "simulate: the body grows into the garment faster than the contact can push it away: morph step %d of %d "
                "is blocked after %d partial moves, which took the body %.1f %% of the step's way",
                blocked.step, morph_steps, blocked.cuts, 100.0 * blocked.done);
  std::string out = text;
  if (blocked.stalled) {
    std::snprintf(text, sizeof text, " (the last %d together %.2g %%: stopped there, as the cloth no longer gives way)",
                  kStallCuts, 100.0 * blocked.last_moves);
    out += text;
  }
  const double ease = garment_ease(loop, body_now, body_faces);  // NaN when either is not measured
  const double around = loop / (1.0 + ease);
  if (std::isfinite(ease) && ease < 0) {
    std::snprintf(text, sizeof text,
                  "; the garment's cloth is %.1f %% shorter around than the body where it stopped (its narrowest loop "
                  "%.3f m at rest, the body's chest or belly %.3f m): the garment does not fit this body (%s)",
                  -100.0 * ease, loop, around,
                  sized ? "size: auto chooses a size at least as large as the body" : "grade: auto grades it to each body");
    return out + text;
  }
  if (std::isfinite(ease)) {
    std::snprintf(text, sizeof text,
                  "; the garment's cloth is %.1f %% longer around than the body there, so its girth is not what blocks it",
                  100.0 * ease);
    out += text;
  }
  // What keeps the cloth from getting out of the body's way.
  std::vector<std::string> causes;
  const Material knit = MaterialTable::builtin().get("gray-interlock");
  double stiffest = 0.0;
  std::string stiffest_name;
  for (const Material& m : garment.materials)
    if (stretch_stiffness(m) > stiffest) stiffest = stretch_stiffness(m), stiffest_name = m.name;
  const double ratio = stiffest / stretch_stiffness(knit);
  if (ratio > 10) {
    std::snprintf(text, sizeof text,
                  "its material '%s' is %.3g times as stiff in stretching as ArcSim's knit (gray-interlock): a cloth that "
                  "barely stretches must be cut larger than the body everywhere, and is pushed out only as fast as it bends",
                  stiffest_name.c_str(), ratio);
    causes.emplace_back(text);
  }
  // A cloth far heavier than a knit is held down on the body's rising
  // shoulders by its weight (an outside check's knit 500 times as heavy was
  // told nothing stood out).
  double heaviest = 0.0;
  std::string heaviest_name;
  for (const Material& m : garment.materials)
    if (m.density > heaviest) heaviest = m.density, heaviest_name = m.name;
  if (const double heavier = heaviest / knit.density; heavier > 10) {
    std::snprintf(text, sizeof text,
                  "its material '%s' is %.3g times as heavy as ArcSim's knit (%.3g kg/m2 against %.3g): its weight holds "
                  "it down on the body's rising shoulders, against the contact",
                  heaviest_name.c_str(), heavier, heaviest, knit.density);
    causes.emplace_back(text);
  }
  // What the scene said of its effects before the run (a stretching of no
  // stiffness, no contact): a cause here too.
  for (const std::string& note : effect_notes) causes.push_back(note);
  // The morph's Newton budget is solver.max_newton_iterations here: the
  // least of max_newton_iterations and morph_newton_iterations.
  for (std::string& slow : slow_solver_settings(solver, [](int n) {
         return "each morph step gets " + std::to_string(n) + " Newton iteration" + (n == 1 ? "" : "s") +
                " (the least of the solver's max_newton_iterations and morph_newton_iterations; 3 by default) to push "
                "the cloth out of the body's way";
       }))
    causes.push_back(std::move(slow));
  double edges = 0.0;
  int count = 0;
  const Eigen::MatrixX3d& x = garment.mesh.vertices;
  for (Eigen::Index f = 0; f < garment.mesh.faces.rows(); ++f)
    for (int k = 0; k < 3; ++k, ++count)
      edges += (x.row(garment.mesh.faces(f, k)) - x.row(garment.mesh.faces(f, (k + 1) % 3))).norm();
  const double mean_edge = count ? edges / count : 0.0;
  if (mean_edge > 0.06) {  // about twice the coarse shirt's
    std::snprintf(text, sizeof text,
                  "its faces are long (edges %.1f cm on average, the coarse shirt's 3.3 cm): a flat face spans the "
                  "body's curves, and the body's growth meets it before the contact can tilt it",
                  100.0 * mean_edge);
    causes.emplace_back(text);
  }
  if (causes.empty()) {
    out += "; nothing in the scene's material, time step or mesh stands out";
  } else {
    out += "; ";
    for (std::size_t i = 0; i < causes.size(); ++i) out += (i ? "; and " : "") + causes[i];
  }
  std::snprintf(text, sizeof text, " (more morph_steps, now %d, give the contact smaller moves to make)", morph_steps);
  return out + text;
}

}  // namespace drape::scene_detail
