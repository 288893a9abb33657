#!/bin/sh
# The network of graphs/drape.yaml trained in drape and in libtorch side by
# side, in one process, on one core (docs/training.md, "Training speed"):
#   scripts/bench_libtorch.sh --data data.h5 [--batch 8] [--steps 10] [--rounds 5]
# The program is built only when CMake found Debian's libtorch-dev; otherwise
# this says so and exits 0.
BUILD_DIR=${BUILD_DIR:-$(dirname "$0")/../build}
exe="$BUILD_DIR/bin/drape-libtorch-bench"
if [ ! -x "$exe" ]; then
  echo "libtorch benchmark skipped: $exe was not built (CMake did not find libtorch; install Debian's libtorch-dev and configure again)"
  exit 0
fi
exec "$exe" "$@"
