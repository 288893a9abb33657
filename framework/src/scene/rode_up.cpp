// garment_rode_up (drape/scene/rode_up.hpp).
#include <drape/scene/rode_up.hpp>

#include <cstdio>

namespace drape {

std::string garment_rode_up(const Eigen::MatrixX3d& modelled, const Eigen::MatrixX3d& draped) {
  if (modelled.rows() == 0 || draped.rows() == 0) return "";
  const double was = modelled.col(1).maxCoeff() - modelled.col(1).minCoeff(),
               is = draped.col(1).maxCoeff() - draped.col(1).minCoeff();
  if (!(was > 0) || !(is < kRodeUpShare * was)) return "";
  char note[320];
  std::snprintf(note, sizeof note,
                "the garment rode up: it spans %.2f m from top to bottom, %.0f %% of the %.2f m it was modelled with; it "
                "is too small round this body to hang as designed (the fit note says how much)",
                is, 100 * is / was, was);
  return note;
}

}  // namespace drape
