#pragma once
// Weight initialisation from a seeded Rng, so a graph seed fixes the weights.
// Fans are explicit: with drape's row-major features x [vertices, in] and
// y = x W, a dense weight W is [in, out], so fan_in = rows, fan_out = cols; a
// convolution's fans also count its kernel taps.
#include <drape/training/rng.hpp>
#include <drape/tensor.hpp>

namespace drape {

// Glorot/Xavier uniform: U(-a, a), a = gain * sqrt(6 / (fan_in + fan_out)). For tanh/sigmoid/linear.
void xavier_uniform(Tensor& weight, int fan_in, int fan_out, Rng& rng, double gain = 1.0);
// He/Kaiming uniform: U(-a, a), a = sqrt(6 / fan_in). For ReLU-like activations.
void he_uniform(Tensor& weight, int fan_in, Rng& rng);
// U(-bound, bound) for biases and anything else.
void uniform_fill(Tensor& weight, double bound, Rng& rng);

}  // namespace drape
