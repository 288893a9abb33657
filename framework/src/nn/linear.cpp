#include <drape/errors.hpp>
#include "matrix_dims.hpp"
#include <drape/nn/gemm.hpp>
#include <drape/nn/linear.hpp>

#include <string>

namespace drape::nn {

void linear_forward(ConstMatRef x, ConstMatRef w, ConstMatRef b, MatRef y) {
  if (x.cols() != w.rows() || b.rows() != 1 || b.cols() != w.cols() || y.rows() != x.rows() || y.cols() != w.cols())
    throw Error("linear_forward: x " + dims(x.rows(), x.cols()) + ", w " + dims(w.rows(), w.cols()) + ", b " +
                dims(b.rows(), b.cols()) + ", y " + dims(y.rows(), y.cols()) + " do not fit");
  gemm(Op::None, Op::None, 1.0f, x, w, 0.0f, y);
  y.rowwise() += b.row(0);
}

void linear_backward_weights(ConstMatRef x, ConstMatRef gy, MatRef gw, MatRef gb) {
  gemm(Op::Transpose, Op::None, 1.0f, x, gy, 1.0f, gw);
  gb.row(0) += gy.colwise().sum();
}

void linear_backward_input(ConstMatRef w, ConstMatRef gy, MatRef gx) { gemm(Op::None, Op::Transpose, 1.0f, gy, w, 0.0f, gx); }

}  // namespace drape::nn
