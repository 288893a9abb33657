// drape body --pose / --pose-file / --sample --poses: a posed body is
// written, bad angles and impossible poses are refused in one line (exit 2),
// and drawing poses leaves a seed's shapes as they were.
#include <catch2/catch.hpp>

#include <drape/io/mesh_io.hpp>

#include <fstream>
#include <sstream>

#include "test_support.hpp"

using namespace drape;

namespace {

std::vector<std::string> lines_of(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::vector<std::string> out;
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// The first `n` comma-separated fields of a line.
std::string first_fields(const std::string& line, int n) {
  std::stringstream s(line);
  std::string field, out;
  for (int i = 0; i < n && std::getline(s, field, ','); ++i) out += field + ",";
  return out;
}

}  // namespace

TEST_CASE("drape body --pose writes the posed body", "[cli][pose]") {
  test::TempDir dir;
  std::string out;
  REQUIRE(test::run_drape("body --bmi 30 --out " + (dir / "rest.obj").string(), out) == 0);
  REQUIRE(test::run_drape("body --bmi 30 --pose shoulder_abduction=90,left_elbow_flexion=60 --out " +
                              (dir / "posed.obj").string(), out) == 0);
  INFO(out);
  CHECK(out.find("posed: left_elbow_flexion=60,left_shoulder_abduction=90,right_shoulder_abduction=90") != std::string::npos);
  const Mesh rest = read_mesh(dir / "rest.obj"), posed = read_mesh(dir / "posed.obj");
  REQUIRE(rest.vertices.rows() == posed.vertices.rows());
  // The right arm raised to horizontal and straight reaches further out than
  // in the A-pose (0.90 against 0.74 m); the left's elbow is bent.
  CHECK(-posed.vertices.col(0).minCoeff() > -rest.vertices.col(0).minCoeff() + 0.1);
  CHECK(posed.vertices.col(0).maxCoeff() < -posed.vertices.col(0).minCoeff() - 0.05);
  {
    std::ofstream(dir / "pose.yaml") << "shoulder_abduction: 90\nleft_elbow_flexion: 60\n";
  }
  REQUIRE(test::run_drape("body --bmi 30 --pose-file " + (dir / "pose.yaml").string() + " --out " +
                              (dir / "file.obj").string(), out) == 0);
  CHECK(read_mesh(dir / "file.obj").vertices == posed.vertices);
}

TEST_CASE("drape body refuses bad or impossible poses in one line", "[cli][pose]") {
  test::TempDir dir;
  std::string out;
  const std::string obj = " --out " + (dir / "b.obj").string();
  CHECK(test::run_drape("body --pose elbo_flexion=30" + obj, out) == 2);
  CHECK(out.find("no joint angle 'elbo_flexion'; did you mean 'elbow_flexion'") != std::string::npos);
  CHECK(test::run_drape("body --pose knee_flexion=nan" + obj, out) == 2);
  CHECK(out.find("left_knee_flexion is NaN") != std::string::npos);
  CHECK(test::run_drape("body --pose spine_twist=90" + obj, out) == 2);
  CHECK(out.find("spine_twist = 90 is outside its range of motion [-45, 45] degrees") != std::string::npos);
  CHECK(test::run_drape("body --bmi 40 --pose shoulder_abduction=0" + obj, out) == 2);
  INFO(out);
  CHECK(out.find("this pose makes the body pass through itself: ") != std::string::npos);
  CHECK(out.find("left_upper_arm into spine_upper (") != std::string::npos);
  CHECK(out.find("joints: left_shoulder_abduction=0)") != std::string::npos);
  CHECK(!std::filesystem::exists(dir / "b.obj"));
  // An elbow folded into its own crease names the elbow (the crease's faces
  // are the upper arm's: "left_upper_arm into itself" named no joint).
  CHECK(test::run_drape("body --bmi 30 --param rig=human --pose left_elbow_flexion=150" + obj, out) == 2);
  CHECK_THAT(out, Catch::Contains("left_upper_arm into itself (") && Catch::Contains("joints: left_elbow_flexion=150)"));
  // An angle several joints share (the spine's bend) is named once (it was "spine_bend=15 spine_bend=15").
  CHECK(test::run_drape("body --bmi 60 --sex 0 --pose spine_bend=15,shoulder_abduction=5" + obj, out) == 2);
  CHECK_THAT(out, Catch::Contains("joints: spine_bend=15 left_shoulder_abduction=5)") && !Catch::Contains("spine_bend=15 spine_bend"));
  // Two shell variables never set ("$A,$B"), or one among others: refused (they were the rest pose).
  for (const std::string pose : {",", "elbow_flexion=30,,knee_flexion=10", ",elbow_flexion=30", ",,"}) {
    CHECK(test::run_drape("body --pose '" + pose + "'" + obj, out) == 2);
    CHECK_THAT(out, Catch::Contains("--pose: an empty item between commas in '" + pose + "'"));
  }
  // A pose file's second YAML document was left out without a word (an
  // elbow of 500 degrees never checked): refused at its line.
  std::ofstream(dir / "two.yaml") << "shoulder_abduction: 60\n...\nelbow_flexion: 500\n";
  CHECK(test::run_drape("body --pose-file " + (dir / "two.yaml").string() + obj, out) == 2);
  CHECK_THAT(out, Catch::Contains("two.yaml:3: a second YAML document"));
  // YAML's infinity read as YAML means it, as its NaN is (it was "not a number of degrees").
  std::ofstream(dir / "inf.yaml") << "elbow_flexion: -.inf\n";
  CHECK(test::run_drape("body --pose-file " + (dir / "inf.yaml").string() + obj, out) == 2);
  CHECK_THAT(out, Catch::Contains("left_elbow_flexion = -inf is outside its range of motion"));
  CHECK(!std::filesystem::exists(dir / "b.obj"));
  // A MakeHuman folder without its rig (rigs/default.mhskel, rigs/default_weights.mhw): refused naming them.
  const auto makehuman = test::shared_assets() / "makehuman";
  if (test::shared_assets().empty() || !std::filesystem::exists(makehuman / "base/base.obj")) return;
  test::TempDir no_rig;
  for (const char* part : {"base", "targets"}) std::filesystem::create_directory_symlink(makehuman / part, no_rig / part);
  CHECK(test::run_drape("body --sample 2 --poses --model makehuman --param path=" + no_rig.path().string() + " --out-dir " +
                            dir.path().string(), out) == 2);
  INFO(out);
  CHECK(out.find("body makehuman: no MakeHuman rig, so it cannot be posed: ") != std::string::npos);
  CHECK(out.find("default_weights.mhw are missing") != std::string::npos);
}

TEST_CASE("drape body --sample --poses keeps the seed's shapes and stores the angles", "[cli][pose]") {
  test::TempDir dir;
  std::string out;
  REQUIRE(test::run_drape("body --sample 3 --seed 4 --out-dir " + (dir / "plain").string(), out) == 0);
  REQUIRE(test::run_drape("body --sample 3 --seed 4 --poses --out-dir " + (dir / "posed").string(), out) == 0);
  INFO(out);
  CHECK(out.find("posed, ") != std::string::npos);
  const auto plain = lines_of(dir / "plain" / "bodies.csv"), posed = lines_of(dir / "posed" / "bodies.csv");
  REQUIRE(plain.size() == 4);
  REQUIRE(posed.size() == 4);
  CHECK(posed[0].find(",pose_left_shoulder_abduction,") != std::string::npos);
  CHECK(posed[0].find(",pose_redraws") != std::string::npos);
  // Index, file, request and the nine shape parameters: the same bodies.
  for (std::size_t i = 1; i < 4; ++i) CHECK(first_fields(posed[i], 14) == first_fields(plain[i], 14));
  CHECK(read_mesh(dir / "plain" / "body_00001.obj").vertices != read_mesh(dir / "posed" / "body_00001.obj").vertices);
}

TEST_CASE("drape simulate refuses bad or impossible poses before simulating", "[cli][pose]") {
  test::TempDir dir;
  std::string out;
  const std::string scene = (test::source_dir() / "graphs" / "scenes" / "tshirt_coarse.yaml").string();
  const std::string obj = " --out " + (dir / "g.obj").string();
  CHECK(test::run_drape("simulate " + scene + " --pose elbo_flexion=30" + obj, out) == 2);
  CHECK(out.find("--pose: no joint angle 'elbo_flexion'; did you mean 'elbow_flexion'") != std::string::npos);
  CHECK(test::run_drape("simulate " + scene + " --pose elbow_flexion=30 --pose-file p.yaml" + obj, out) == 2);
  CHECK(out.find("--pose, --pose-file and --smpl-theta: give one") != std::string::npos);
  // A pose file that is not there is named with its option (it said "cannot read 'p.yaml'").
  CHECK(test::run_drape("simulate " + scene + " --pose-file " + (dir / "none.yaml").string() + obj, out) == 2);
  CHECK(out.find("--pose-file " + (dir / "none.yaml").string() + ": no such file") != std::string::npos);
  CHECK(test::run_drape("simulate " + scene + " --bmi 40 --pose shoulder_abduction=0" + obj, out) == 2);
  CHECK(out.find("left_upper_arm into spine_upper (") != std::string::npos);
  // A scene's pose is refused at its line.
  std::ofstream(dir / "posed.yaml") << "base: " << scene << "\nbody:\n  pose: {knee_flexion: 200}\n";
  CHECK(test::run_drape("simulate " + (dir / "posed.yaml").string() + obj, out) == 2);
  INFO(out);
  CHECK(out.find("posed.yaml:3: body `pose`: left_knee_flexion = 200 is outside its range of motion") != std::string::npos);
  CHECK(!std::filesystem::exists(dir / "g.obj"));
}
