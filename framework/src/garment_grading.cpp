// grade_garment (garment_grading.hpp).
#include <drape/errors.hpp>
#include <drape/garment_grading.hpp>

#include <string>

namespace drape {

void grade_garment(Garment& garment, double grade) {
  if (!(grade >= kMinGrade && grade <= kMaxGrade))
    throw ConfigError("garment grade " + std::to_string(grade) + " is outside " + std::to_string(kMinGrade) + " to " +
                      std::to_string(kMaxGrade));
  if (grade == 1.0) return;
  Eigen::MatrixX3d& x = garment.mesh.vertices;
  if (x.rows() == 0) return;
  const Eigen::RowVector3d top(x.col(0).mean(), x.col(1).maxCoeff(), x.col(2).mean());
  x = ((x.rowwise() - top) * grade).rowwise() + top;
  if (garment.mesh.has_uv()) garment.mesh.uv *= grade;
}

}  // namespace drape
