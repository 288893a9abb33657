#pragma once
// Grading a garment to another size, as a tailor grades a pattern: every
// girth and every length scaled by one factor. The rest garment (as its
// template built it, before dressing) is scaled about the centre of its top
// (mean x and z of its vertices, its highest y), so a shirt keeps its neckline
// at the neck while it grows around and down; its material space (UVs, the
// flat pattern) is scaled by the same factor, so the cloth's rest lengths
// grow with it. A scene asks for it with `garment: {grade: g}` (any
// template), and datasets record it in their scene text.
#include <drape/energy.hpp>  // Garment

namespace drape {

inline constexpr double kMinGrade = 0.5, kMaxGrade = 2.0;

// Scales `garment` in place by `grade` (ConfigError outside [kMinGrade, kMaxGrade]).
void grade_garment(Garment& garment, double grade);

}  // namespace drape
