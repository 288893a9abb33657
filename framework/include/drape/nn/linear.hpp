#pragma once
// The dense layer on row-major features: y = x w + b with x [N, in], w [in, out],
// b [1, out], y [N, out]. Rows are independent (vertices, or samples of a batch
// stacked with Tensor::flat()), so one matrix product serves a whole batch.
#include <drape/nn/refs.hpp>

namespace drape::nn {

void linear_forward(ConstMatRef x, ConstMatRef w, ConstMatRef b, MatRef y);
// gw += x^T gy, gb += sum over rows of gy.
void linear_backward_weights(ConstMatRef x, ConstMatRef gy, MatRef gw, MatRef gb);
// gx = gy w^T (overwrites).
void linear_backward_input(ConstMatRef w, ConstMatRef gy, MatRef gx);

}  // namespace drape::nn
