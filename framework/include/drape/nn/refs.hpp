#pragma once
// Matrix views the nn building blocks take: any row-major float matrix with
// contiguous rows (a Tensor's mat()/flat(), a MatrixRM, a block of rows) binds
// without a copy.
#include <drape/tensor.hpp>

#include <Eigen/Core>

namespace drape::nn {

using ConstMatRef = Eigen::Ref<const MatrixRM>;
using MatRef = Eigen::Ref<MatrixRM>;

}  // namespace drape::nn
