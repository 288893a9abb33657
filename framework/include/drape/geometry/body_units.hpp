#pragma once
// Is a body mesh a user brings in drape's frame and units? Checked before any
// work, in every command and in Python: a body exported in centimetres once
// ran for 13 minutes before a contact error blamed the garment's fit, and a
// coordinate of 1e308 was blamed on the model. drape's bodies are in metres,
// Y up, standing (A-pose): a person's height lies within kHeightRange and is
// the body's longest extent.
#include <Eigen/Core>

#include <string>

namespace drape {

// Heights (m) drape takes for a body: a toddler to the tallest person recorded (2.72 m).
struct HeightRange {
  static constexpr double min = 0.4, max = 2.8;
};

// m: the farthest a body's coordinates may lie from the origin for the
// network's single precision to hold them to 0.03 mm (half a float's step
// below 1,024 m). A body mesh beyond it is moved near the origin in double
// before it is narrowed (drape predict), or refused where what is returned
// is single precision itself (the Python module's float32 arrays).
inline constexpr double kFloatExactReach = 1000.0;
// m: how far a float may round a coordinate of magnitude |x| (half its step
// there): 0.03 mm below 1,024 m, 31 mm at 1e6 m. Said in the refusals and
// notes of a body far from the origin.
double float_rounding(double x);

// "" when the body passes; else one line that starts with `what` and gives
// the likely cause: a non-finite or absurd coordinate (named), a size in
// other units (with the power of ten that would fit), or a body lying along
// z or x rather than standing along y.
std::string body_units_problem(const Eigen::MatrixX3d& body, const std::string& what);

// Throws drape::ConfigError with body_units_problem's line when there is one.
void check_body_units(const Eigen::MatrixX3d& body, const std::string& what);

}  // namespace drape
