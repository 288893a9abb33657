#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include <drape/nn/gemm.hpp>

int main(int argc, char** argv) {
  // The same BLAS kernels as the drape program (it re-executes itself the same
  // way), so that a test comparing a run in this process with one of the
  // command line compares like with like.
  drape::nn::reexec_with_native_blas(argv);
  return Catch::Session().run(argc, argv);
}
