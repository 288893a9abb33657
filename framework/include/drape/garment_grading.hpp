#pragma once
// Grading a garment to another size, as a tailor grades a pattern: every
// girth (width) scaled by the grade g, every length by grade_length(g) =
// 1 + 0.3 (g - 1), as ready-to-wear size charts grow a tee's chest by about
// 5 cm a size and its body length by about 2.5 cm (a 6xlarge of twice the
// chest is 30 % longer, not twice as long).
//
// The rest garment (as its template built it, before dressing) is scaled
// about the centre of its top (mean x and z of its vertices, its highest y):
// x and z by g, y by grade_length(g), so a shirt keeps its neckline at the
// neck while it grows around and a little down. Its material space (the
// pattern's UVs) is graded with it, chart by chart: along the direction in
// which the chart rises in 3D (the least-squares gradient of the vertices'
// height over its UVs) by the 3D factor of that slope, across it by g. Its
// fit_grade is multiplied by g, so that a scene dresses it on a body of
// that girth (drape/bodies/fit_body.hpp). A scene asks for it with
// `garment: {grade: g}` (any template), and datasets record it in their
// scene text.
#include <drape/energy.hpp>  // Garment

#include <limits>

namespace drape {

inline constexpr double kMinGrade = 0.5, kMaxGrade = 2.0;

// How much a grade of girth g grows lengths: 1 + 0.3 (g - 1).
inline constexpr double kLengthPerGirth = 0.3;
inline double grade_length(double g) { return 1.0 + kLengthPerGirth * (g - 1.0); }

// Grades `garment` in place by `grade` (ConfigError outside [kMinGrade, kMaxGrade]).
// `legs_below` and `floor` (m, heights: the crotch and the soles of the
// mean body the garment is modelled around; NaN: not known): when a piece
// of the garment (a connected part of its mesh) reaches below the crotch --
// trousers, a dress -- the heights below the crotch are taken in evenly
// between where the length grade puts the crotch and the floor, which is
// kept, and that piece's cloth keeps its lengths (an inseam does not grow
// with the waist). One map of heights for all pieces, so that grading passes
// no piece through another. Graded about its top alone, MakeHuman's suit at
// grade 1.35 had its jeans' hems 16 cm down, through the feet and the floor,
// and its start was refused (an outside check).
void grade_garment(Garment& garment, double grade, double legs_below = std::numeric_limits<double>::quiet_NaN(),
                   double floor = std::numeric_limits<double>::quiet_NaN());

// Grades only the material space (UVs) of `mesh` (its vertices at rest, read
// for the charts' rise) as grade_garment grades a garment's, by any grade
// > 0 (ConfigError else): a template's sizes beyond 2 (6xlarge's 2.02) rest
// at lengths that a garment graded there would have. Nothing else changes.
void grade_material(Mesh& mesh, double grade);

// Places a garment graded by `grade` on the body it is cut for by that body's
// own growth, instead of the uniform scale about its top: each vertex of the
// ungraded garment (`ungraded`, around `mean_body`) keeps the point of the
// mean body nearest it (face and barycentric coordinates), follows that point
// to `fit_body` (the same topology) and keeps its offset from it scaled by the
// grade, its height below the garment's top by grade_length (the moves then
// smoothed over the garment, so that cloth between two parts of the body, an
// armpit's, does not fold through itself). A uniform scale
// leaves a larger size crossing a fit body that grew unevenly: MakeHuman's
// shirt graded to 1.35 started through its fit body's chest (docs/garments.md,
// "A user's MakeHuman top over BMI 15-32"). The material space is
// grade_garment's, untouched.
// Lengths as grade_garment's (`legs_below` and `floor` likewise).
void place_graded_garment(Garment& garment, const Eigen::MatrixX3d& ungraded, const Eigen::MatrixX3d& mean_body,
                          const Eigen::MatrixX3d& fit_body, const Eigen::MatrixX3i& body_faces, double grade,
                          double legs_below = std::numeric_limits<double>::quiet_NaN(),
                          double floor = std::numeric_limits<double>::quiet_NaN());

}  // namespace drape
