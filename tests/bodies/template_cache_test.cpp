// The parametric body's template cache (plugins/bodies/parametric/
// template_cache.hpp), through the program as a user meets it: a body made
// with the template read back is the body made with it meshed, and a cache
// file that is damaged, from another build, or cannot be written changes
// nothing but the time.
#include <drape/io/h5.hpp>

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "test_support.hpp"

namespace fs = std::filesystem;
using namespace drape;

namespace {

// `drape body` of one shape with the given cache folder; the OBJ's text (17 digits: every bit).
std::string body_with_cache(const fs::path& cache, const fs::path& out) {
  std::string log;
  REQUIRE(test::run("env DRAPE_CACHE_DIR=" + cache.string() + " " + test::drape_program().string() +
                        " body --bmi 37 --height 1.62 --sex 0.2 --out " + out.string(),
                    log) == 0);
  return test::read_file(out);
}

std::vector<fs::path> template_files(const fs::path& cache) {
  std::vector<fs::path> out;
  if (fs::exists(cache))
    for (const auto& e : fs::directory_iterator(cache))
      if (e.path().filename().string().rfind("parametric-template-", 0) == 0) out.push_back(e.path());
  return out;
}

}  // namespace

TEST_CASE("parametric body: a template read from the cache makes the body a meshed one makes, and a bad cache file is meshed again",
          "[bodies][cache]") {
  test::TempDir dir;
  const fs::path cache = dir / "cache";
  const std::string meshed = body_with_cache(cache, dir / "a.obj");
  const auto files = template_files(cache);
  REQUIRE(files.size() == 1);
  const fs::path file = files.front();
  {
    const h5::File f = h5::File::open(file);
    CHECK(f.shape("vertices") == h5::Dims{6490, 3});
    CHECK(f.shape("faces") == h5::Dims{12976, 3});
    CHECK(f.string_attribute("/", "key").value_or("").find("parametric body template") == 0);
  }
  // Read back: the same body to the last digit, and nothing rewritten.
  const auto written = fs::last_write_time(file);
  CHECK(body_with_cache(cache, dir / "b.obj") == meshed);
  CHECK(fs::last_write_time(file) == written);

  SECTION("a damaged file") {
    std::ofstream(file, std::ios::binary | std::ios::trunc) << "not an HDF5 file";
    CHECK(body_with_cache(cache, dir / "c.obj") == meshed);
    CHECK(h5::File::open(file).shape("vertices") == h5::Dims{6490, 3});  // rewritten
  }
  SECTION("a file of another build: its key differs, so its mesh is not used") {
    std::vector<double> v;
    h5::Dims vdims;
    {
      const h5::File f = h5::File::open(file);
      v = f.read<double>("vertices", &vdims);
    }
    for (double& x : v) x *= 1.01;  // a template that would make other bodies
    {
      h5::File f = h5::File::open(file, h5::Access::ReadWrite);
      f.write("vertices", vdims, v.data());
      f.set_attribute("/", "key", "parametric body template 1; rig 0; target 6500; plugin (another build)");
    }
    CHECK(body_with_cache(cache, dir / "d.obj") == meshed);
    CHECK(h5::File::open(file).string_attribute("/", "key").value_or("").find("another build") == std::string::npos);
  }
  SECTION("a cache folder that cannot be made") {
    const fs::path blocked = dir / "blocked";
    std::ofstream(blocked) << "a file where the folder would be";
    CHECK(body_with_cache(blocked / "cache", dir / "e.obj") == meshed);
  }
}
