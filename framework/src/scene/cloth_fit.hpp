#pragma once
// What a garment's cloth measures around (its material space: the cloth at
// rest) against a body, in words, for the two places a scene learns that a
// garment does not go on: before the first step (the body it is put on is
// larger around than the cloth can be stretched to) and when a morph step
// stalls (barrier_morph.hpp), where the girth says whether the garment is
// too small or something else holds the cloth back.
#include "barrier_morph.hpp"

#include <drape/energy.hpp>
#include <drape/physics/solver.hpp>

#include <Eigen/Core>

#include <functional>
#include <string>
#include <vector>

namespace drape::scene_detail {

// A garment must go around the body it is put on, stretched by at most
// this much around (its cloth's narrowest loop over the chest band at
// least 1 / 1.25 = 80 % of the body's chest or belly). Measured: the coarse
// shirt cut to 0.7 of its pattern (a loop of 0.787 m at rest around the
// mean body's 1.016 m, 29 % to stretch) dressed without crossing, then took
// 55 s to a drape whose edges were stretched by 11 % at the median and up
// to 107 %; every shipped garment starts with 0.7-9.6 % more cloth around
// than the body.
inline constexpr double kMaxStartStretch = 0.25;

// How a scene's garment gets its material space, for the remedy a refusal
// names. A grade is not one: a graded garment is put on the body of its
// girth (fit_body.hpp), so its cloth and that body grow alike.
struct PatternSource {
  bool has_uv_scale = false;  // the template takes uv_scale (the mesh garment)
  double uv_scale = 1.0;      // its value in the scene
  bool from_shape = false;    // material_space: rest (the shape laid flat is the cloth)
  double grade = 1.0;         // the scene's garment grade (garment: {grade: g}), which scales the cloth
};

// "" when the garment's cloth goes around `start_body` (the body the morph
// starts from) stretched by no more than kMaxStartStretch, or cannot be
// measured (no material space, or no loop around the torso); else why not,
// with what makes the cloth as long around as the body.
// `loop`: the cloth's narrowest loop at rest (garment_material_girth, NaN
// when it has none), measured once by the caller for every question here.
std::string cloth_too_short(double loop, const Eigen::MatrixX3d& start_body, const Eigen::MatrixX3i& body_faces,
                            const PatternSource& pattern);

// A garment modelled much larger around than its cloth (its 3D loop over the
// chest band more than kMaxStartStretch longer than the same loop at rest):
// it starts stretched by that much and pulls in as it settles, which is
// seldom what a user meant (UVs in another unit, a uv_scale for another
// file). "" otherwise, or when either loop cannot be measured; else a note
// with the uv_scale that makes the cloth the size of the shape.
std::string shape_larger_than_cloth(double cloth_loop, double shape_loop, const PatternSource& pattern);

// Cloth this many times as long around as the garment's shape is no garment
// as modelled (every shipped garment's cloth is within 10 % of its shape):
// its UVs are in another unit (feet to metres is 3.28, the nearest). An
// outside check's vest with UVs in centimetres ran 330 s before the morph
// failed, "10260.6 % longer around". A shape shrunk to half its pattern (2x)
// is left to the placement's own refusal (placed through the body).
inline constexpr double kMaxClothOverShape = 3.0;

// The refusal, with the uv_scale that makes the cloth the size of the shape,
// when the cloth's narrowest loop at rest is more than kMaxClothOverShape
// times the same loop as modelled; "" otherwise, or when either is not measured.
std::string cloth_far_longer_than_shape(double cloth_loop, double shape_loop, const PatternSource& pattern);

// Solver settings far from their defaults that keep the cloth from moving
// far a step, in words for a run's "why": a time step under a tenth of the
// default, a Newton budget under kFewNewtonIterations (the morph's default
// budget), said by `newton` given the count (the morph's budget and the
// settling's are named differently). An outside check's time step of 1e-5 s
// was told of a pinched garment.
inline constexpr int kFewNewtonIterations = 3;
std::vector<std::string> slow_solver_settings(const SolverSettings& solver, const std::function<std::string(int)>& newton);

// Why the morph stalled, in words: what the body made of the step, the
// cloth's girth against the body's there, and when that is not the cause,
// what in the scene keeps the cloth from giving way (a stiff material, a
// short time step, long faces, a heavy material, and `effect_notes`:
// Simulation::effect_notes, what the scene's effects leave out). `sized`:
// the garment has sizes to choose from (else grade: auto is the remedy to name).
std::string why_morph_blocked(const MorphBlocked& blocked, int morph_steps, const Garment& garment, double cloth_loop,
                              const Eigen::MatrixX3d& body_now, const Eigen::MatrixX3i& body_faces,
                              const SolverSettings& solver, bool sized, const std::vector<std::string>& effect_notes = {});

}  // namespace drape::scene_detail
