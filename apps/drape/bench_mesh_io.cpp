// `drape bench mesh-io FILE`: how long reading FILE takes, and writing and
// reading it back in every format (best of several runs, wall time), with a
// check that each round trip kept vertex count and faces.
#include "bench.hpp"

#include <drape/io/mesh_io.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <random>

namespace drape::cli {
namespace DRAPE_UNITY_ID {  // the anonymous namespace, or a unique one in a unity build (command.hpp)

namespace fs = std::filesystem;

double best_ms(int repeats, const std::function<void()>& action) {
  double best = 1e300;
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    action();
    best = std::min(best, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  return best;
}

int run(const std::vector<std::string>& args) {
  po::options_description opts("drape bench mesh-io");
  opts.add_options()("file", po::value<std::string>()->required(), "mesh to read (e.g. MakeHuman base.obj)")(
      "repeats", po::value<int>()->default_value(5), "runs per measurement; the best is shown");
  po::positional_options_description positional;
  positional.add("file", 1);
  po::variables_map vm;
  if (!parse("drape bench mesh-io FILE [--repeats N]", args, opts, positional, vm)) return 0;
  const fs::path file = vm["file"].as<std::string>();
  const int repeats = count_option(vm, "repeats");

  Mesh mesh;
  const double read_ms = best_ms(repeats, [&] { mesh = read_mesh(file); });
  std::printf("%s: %d vertices, %d triangles, %d uv rows\n", file.filename().c_str(), mesh.num_vertices(),
              mesh.num_faces(), static_cast<int>(mesh.uv.rows()));
  std::printf("%-8s %10s %10s %12s  %s\n", "format", "write ms", "read ms", "size bytes", "round trip");
  std::printf("%-8s %10s %10.2f %12ju  %s\n", "(input)", "-", read_ms, static_cast<std::uintmax_t>(fs::file_size(file)), "-");

  std::random_device rd;
  const fs::path dir = fs::temp_directory_path() / ("drape-bench-mesh-io-" + std::to_string(rd()));
  fs::create_directories(dir);
  int failures = 0;
  for (const char* ext : {".obj", ".ply", ".gltf", ".glb"}) {
    const fs::path out = dir / (std::string("mesh") + ext);
    const double write_ms = best_ms(repeats, [&] { write_mesh(out, mesh); });
    Mesh back;
    const double back_ms = best_ms(repeats, [&] { back = read_mesh(out); });
    const bool kept = back.num_vertices() == mesh.num_vertices() && back.faces == mesh.faces;
    failures += kept ? 0 : 1;
    std::printf("%-8s %10.2f %10.2f %12ju  %s\n", ext, write_ms, back_ms, static_cast<std::uintmax_t>(fs::file_size(out)),
                kept ? "order and count kept" : "CHANGED");
  }
  std::error_code ec;
  fs::remove_all(dir, ec);
  return failures == 0 ? 0 : 1;
}

const RegisterBench registration{{"mesh-io", "time mesh reading and writing in every format", run}};

}  // namespace
}  // namespace drape::cli
