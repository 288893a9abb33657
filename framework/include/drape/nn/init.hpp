#pragma once
// Weight initialisation. Every layer draws from its own stream derived from the
// node's seed (NodeContext::seed) and a salt, so adding a layer does not change
// the others' initial values and runs are reproducible.
#include <drape/nn/activation.hpp>
#include <drape/tensor.hpp>

#include <cstdint>

namespace drape::nn {

// A well-mixed 64-bit seed from `seed` and `salt` (splitmix64).
std::uint64_t mix_seed(std::uint64_t seed, std::uint64_t salt);

// He (Kaiming) standard deviation for a layer followed by `f`: sqrt(gain^2 / fan_in)
// with gain^2 = 2 / (1 + slope^2) for the ReLU family and 1 otherwise.
float he_std(const Activation& f, int fan_in);

// Fills `w` with N(0, std^2) values from the stream `seed`.
void fill_normal(Tensor& w, float std, std::uint64_t seed);

}  // namespace drape::nn
