// A model's training domain (model_domain.hpp): its ranges against values
// derived from how the tiny dataset was made (body i is the mean body grown by
// 1 + a_i about its centroid, a_i drawn as train_test_util.hpp draws them), a
// body outside named by measure, and predict warning or refusing (--strict).
#include <catch2/catch.hpp>

#include <drape/io/output_lock.hpp>

#include "train_test_util.hpp"

#include <drape/geometry/volume.hpp>
#include <drape/io/h5.hpp>
#include <drape/io/mesh_io.hpp>
#include <drape/training/model_domain.hpp>

using namespace drape;
namespace fs = std::filesystem;

namespace {

// The growth factors 1 + a_i of the tiny dataset's first n_train samples.
std::pair<double, double> training_growth(int n_train, std::uint64_t seed = 3) {
  Rng rng(seed);
  double lo = 1e9, hi = -1e9;
  for (int i = 0; i < n_train; ++i) {
    const double s = 1.0 + rng.uniform(0.0, 0.2);
    lo = std::min(lo, s);
    hi = std::max(hi, s);
  }
  return {lo, hi};
}

// All of them, in order.
std::vector<double> training_growths(int n_train, std::uint64_t seed = 3) {
  Rng rng(seed);
  std::vector<double> s;
  for (int i = 0; i < n_train; ++i) s.push_back(1.0 + rng.uniform(0.0, 0.2));
  return s;
}

Eigen::MatrixX3d grown(const Eigen::MatrixX3d& body, double s) {
  const Eigen::RowVector3d c = body.colwise().mean();
  return c.replicate(body.rows(), 1) + s * (body.rowwise() - c);
}

std::vector<std::string> param_names(int n) {
  std::vector<std::string> names;
  for (int i = 0; i < n; ++i) names.push_back("p" + std::to_string(i));
  return names;
}

bool mentions(const std::vector<std::string>& lines, const std::string& what) {
  for (const auto& l : lines)
    if (l.find(what) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("model domain: ranges of a dataset's training bodies, and the bodies outside them", "[train][domain]") {
  test::TempDir dir;
  test::write_tiny_dataset(dir / "data.h5", 12, 8, 2);
  const auto assets = test::tiny_assets();
  const Eigen::MatrixX3d& mean = assets->body.vertices;
  const Eigen::MatrixX3i& faces = assets->body.faces;
  const DatasetReader data(dir / "data.h5");
  const int P = data.layout().body_params;
  const ModelDomain d = domain_of_dataset(data, "parametric", param_names(P), faces);

  // Height grows with s, volume with s^3, so BMI = volume * 985 / height^2 with s.
  const auto [lo, hi] = training_growth(8);
  const double h0 = mean.col(1).maxCoeff() - mean.col(1).minCoeff();
  const double bmi0 = geometry::mesh_volume(mean, faces) * 985.0 / (h0 * h0);
  CHECK(d.samples == 8);
  CHECK(d.height.min == Approx(lo * h0).epsilon(1e-5));
  CHECK(d.height.max == Approx(hi * h0).epsilon(1e-5));
  CHECK(d.bmi.min == Approx(lo * bmi0).epsilon(1e-4));
  CHECK(d.bmi.max == Approx(hi * bmi0).epsilon(1e-4));
  // Parameter 0 was raised by a = s - 1; the others are the mean shape's.
  CHECK(d.params[0].max - d.params[0].min == Approx(hi - lo).epsilon(1e-4));
  for (int p = 1; p < P; ++p) CHECK(d.params[static_cast<std::size_t>(p)].min == d.params[static_cast<std::size_t>(p)].max);
  // drape train --fraction 0.5 trains on the first half of them: its domain is theirs.
  const ModelDomain half = domain_of_dataset(data, "parametric", param_names(P), faces, 0.5);
  CHECK(half.samples == 4);
  CHECK(half.height.max - half.height.min < d.height.max - d.height.min);

  SECTION("a body between the training bodies is inside") {
    CHECK(domain_violations(d, grown(mean, 0.5 * (lo + hi)), faces, nullptr).empty());
  }
  SECTION("a body larger than any is outside in height, BMI and shape, each named") {
    const auto why = domain_violations(d, grown(mean, hi + 0.3), faces, nullptr);
    CHECK(mentions(why, "height"));
    CHECK(mentions(why, "BMI"));
    CHECK(mentions(why, "from the nearest of the 8 training bodies"));
  }
  SECTION("a body of the right height and volume but another shape is outside by its distance") {
    // Wider and shallower by the same factor: height and volume (so BMI) unchanged.
    Eigen::MatrixX3d other = grown(mean, 0.5 * (lo + hi));
    const Eigen::RowVector3d c = other.colwise().mean();
    other.col(0) = (other.col(0).array() - c(0)) * 1.25 + c(0);
    other.col(2) = (other.col(2).array() - c(2)) / 1.25 + c(2);
    const auto why = domain_violations(d, other, faces, nullptr);
    REQUIRE(why.size() == 1);
    CHECK(mentions(why, "cm (RMS) from the nearest"));
  }
  SECTION("a shape parameter outside its range is named") {
    Eigen::VectorXd params = Eigen::VectorXd::Zero(P);
    for (int p = 0; p < P; ++p) params(p) = d.params[static_cast<std::size_t>(p)].min;
    CHECK(domain_violations(d, grown(mean, lo), faces, &params).empty());
    params(P - 1) += 1.0;
    CHECK(mentions(domain_violations(d, grown(mean, lo), faces, &params), "shape parameter 'p" + std::to_string(P - 1) + "'"));
  }
  SECTION("where the training bodies stood, and a body standing elsewhere") {
    // Grown about its centroid, body i keeps the mean body's centroid and
    // has its soles at cy + s_i (y_min - cy).
    const Eigen::RowVector3d c = mean.colwise().mean();
    const double y_min = mean.col(1).minCoeff();
    double y_mean = 0, y_spread = 0;
    const std::vector<double> s = training_growths(8);
    for (double si : s) y_mean += (c[1] + si * (y_min - c[1])) / static_cast<double>(s.size());
    for (double si : s) y_spread = std::max(y_spread, std::abs(c[1] + si * (y_min - c[1]) - y_mean));
    CHECK(d.placement[0] == Approx(c[0]).margin(1e-6));
    CHECK(d.placement[1] == Approx(y_mean).margin(1e-6));
    CHECK(d.placement[2] == Approx(c[2]).margin(1e-6));
    CHECK(d.placement_spread[0] == Approx(0).margin(1e-6));
    CHECK(d.placement_spread[1] == Approx(y_spread).margin(1e-6));
    CHECK(y_spread > 1e-3);  // the test means something: the soles differ

    const Eigen::MatrixX3d inside = grown(mean, 0.5 * (lo + hi));
    CHECK_FALSE(placement_offset(d, inside));
    Eigen::MatrixX3d lifted = inside;
    lifted.col(1).array() += 5.0;
    const auto up = placement_offset(d, lifted);
    REQUIRE(up);
    // Only the axis outside the spread: x and z are the body's own.
    CHECK((*up)[0] == 0.0);
    CHECK((*up)[2] == 0.0);
    CHECK((*up)[1] == Approx(5.0 + lifted.col(1).minCoeff() - 5.0 - y_mean).margin(1e-9));
    Eigen::MatrixX3d aside = inside;
    aside.col(0).array() += 0.3;
    const auto moved = placement_offset(d, aside);
    REQUIRE(moved);
    CHECK((*moved)[0] == Approx(0.3).margin(1e-9));
    CHECK((*moved)[1] == 0.0);
    // Inside by shape, the lifted body is not a violation: it is only moved.
    CHECK(domain_violations(d, lifted, faces, nullptr).empty());

    // The note says a move under a centimetre in millimetres (it said "(+0.000, +0.000, +0.000) m").
    CHECK_THAT(placement_note({0.3, 0, 0}, "x"), Catch::StartsWith("stands (+0.300, +0.000, +0.000) m from where x"));
    CHECK_THAT(placement_note({0.0004, 0, -0.00125}, "x"), Catch::StartsWith("stands (+0.40, +0.00, -1.25) mm from where x"));

    ModelDomain unrecorded = d;
    unrecorded.placement.setConstant(std::numeric_limits<double>::quiet_NaN());
    CHECK_FALSE(placement_offset(unrecorded, lifted));
  }
  SECTION("a mesh in millimetres, or lying along z, is named as such") {
    CHECK(mentions(domain_violations(d, 1000.0 * grown(mean, lo), faces, nullptr), "millimetres"));
    Eigen::MatrixX3d z_up = grown(mean, lo);
    z_up.col(1).swap(z_up.col(2));
    CHECK(mentions(domain_violations(d, z_up, faces, nullptr), "longer along z than along y"));
  }
  SECTION("written into a file and read back unchanged") {
    {
      h5::File f = h5::File::create(dir / "m.h5");
      write_domain(f, d);
      f.close();
    }
    const auto back = read_domain(dir / "m.h5");
    REQUIRE(back);
    CHECK(back->param_names == d.param_names);
    CHECK(back->height.min == d.height.min);
    CHECK(back->bmi.max == d.bmi.max);
    CHECK(back->descriptors == d.descriptors);
    CHECK(back->neighbour_limit == d.neighbour_limit);
    CHECK(back->descriptor_vertices == d.descriptor_vertices);
    CHECK(back->placement == d.placement);
    CHECK(back->placement_spread == d.placement_spread);
  }
  SECTION("a file from before the placement was recorded reads without it") {
    ModelDomain old = d;
    old.placement.setConstant(std::numeric_limits<double>::quiet_NaN());
    {
      h5::File f = h5::File::create(dir / "old.h5");
      write_domain(f, old);
      f.close();
    }
    const auto back = read_domain(dir / "old.h5");
    REQUIRE(back);
    CHECK_FALSE(h5::File::open(dir / "old.h5").exists("/domain/placement"));
    CHECK_FALSE(back->placement.allFinite());
    CHECK(back->descriptors == d.descriptors);
  }
}

TEST_CASE("model domain: a body trained on twice (a drape and its mirror image) is not its own nearest neighbour",
          "[train][domain]") {
  // The same 8 training bodies, and the same again in a second file: what a
  // posed dataset with its mirrored drapes holds (scripts/mirror_dataset.py:
  // a mirrored drape's body is its original's, at rest).
  test::TempDir dir;
  fs::create_directories(dir / "once");
  fs::create_directories(dir / "twice");
  test::write_tiny_dataset(dir / "once" / "a.h5", 12, 8, 2);
  test::write_tiny_dataset(dir / "twice" / "a.h5", 12, 8, 2);
  test::write_tiny_dataset(dir / "twice" / "b.h5", 12, 8, 2);
  const Eigen::MatrixX3i& faces = test::tiny_assets()->body.faces;
  const DatasetReader once((dir / "once" / "a.h5").string()), twice((dir / "twice" / "*.h5").string());
  const int P = once.layout().body_params;
  const ModelDomain d = domain_of_dataset(once, "parametric", param_names(P), faces);
  const ModelDomain twins = domain_of_dataset(twice, "parametric", param_names(P), faces);
  REQUIRE(twins.samples == 2 * d.samples);
  REQUIRE(d.neighbour_limit > 0.011);  // above the 1 cm floor, so twins counted as neighbours would show
  CHECK(twins.neighbour_limit == Approx(d.neighbour_limit).epsilon(1e-12));
  // Stored once: the twins add nothing to the model file or to a check's scan.
  CHECK(twins.descriptors.rows() == d.descriptors.rows());
  CHECK(twins.descriptors == d.descriptors);
  // Said as both counts where they differ, as one where they do not.
  CHECK(training_count(d) == std::to_string(d.samples) + " training bodies");
  CHECK(training_count(twins) ==
        std::to_string(2 * d.samples) + " training samples (" + std::to_string(d.descriptors.rows()) + " distinct bodies)");
}

TEST_CASE("drape model domain records it: predict warns outside it and --strict refuses", "[train][domain][cli]") {
  test::TempDir dir;
  const fs::path data = dir / "data.h5", model = dir / "model.h5";
  test::write_tiny_dataset(data, 14, 8, 3);
  auto o = test::tiny_training(data, model);
  o.epochs = 1;
  train(test::plugins(), o);
  std::string out;
  REQUIRE(test::run(test::drape_command("model info " + model.string()), out) == 0);
  CHECK_THAT(out, Catch::Contains("domain: not recorded"));
  REQUIRE(test::run(test::drape_command("predict --model " + model.string() + " --bmi 45 --strict --out " +
                                        (dir / "g.obj").string()),
                    out) == 2);
  CHECK_THAT(out, Catch::Contains("records no training domain"));

  {
    // One writer per output: a job holding the output's lock (a generate making a set of that name) is not
    // written over (model domain wrote its model, then the generate renamed its dataset over it).
    const OutputLock busy(dir / "busy.h5", "drape generate");
    CHECK(test::run(test::drape_command("model domain " + model.string() + " --data " + data.string() + " --out " +
                                        (dir / "busy.h5").string()),
                    out) == 2);
    CHECK_THAT(out, Catch::Contains("drape generate"));
    CHECK(test::run(test::drape_command("model set " + model.string() + " --set post.enabled=false --out " +
                                        (dir / "busy.h5").string()),
                    out) == 2);
    CHECK_THAT(out, Catch::Contains("drape generate"));
    CHECK_FALSE(fs::exists(dir / "busy.h5"));
  }
  REQUIRE(test::run(test::drape_command("model domain " + model.string() + " --data " + data.string()), out) == 0);
  REQUIRE(test::run(test::drape_command("model info " + model.string()), out) == 0);
  CHECK_THAT(out, Catch::Contains("8 training bodies from data.h5"));
  {
    // The same bodies twice (a dataset with its mirror images): the samples
    // and the distinct bodies both said.
    fs::create_directories(dir / "twins");
    fs::copy_file(data, dir / "twins" / "a.h5");
    fs::copy_file(data, dir / "twins" / "b.h5");
    const fs::path twins = dir / "twins.h5";
    // (Another name than the model's training data: refused unless --force.)
    CHECK(test::run(test::drape_command("model domain " + model.string() + " --data '" + (dir / "twins" / "*.h5").string() +
                                        "' --out " + twins.string()),
                    out) == 2);
    CHECK_THAT(out, Catch::Contains("was trained on data.h5 (its meta 'dataset'), not ") && Catch::Contains("--force"));
    CHECK_FALSE(fs::exists(twins));
    REQUIRE(test::run(test::drape_command("model domain " + model.string() + " --data '" + (dir / "twins" / "*.h5").string() +
                                          "' --out " + twins.string() + " --force"),
                      out) == 0);
    REQUIRE(test::run(test::drape_command("model info " + twins.string()), out) == 0);
    CHECK_THAT(out, Catch::Contains("16 training samples (8 distinct bodies) from"));
  }
  // The training bodies are the mean body grown by at most 1.2: BMI 45 is far outside.
  REQUIRE(test::run(test::drape_command("predict --model " + model.string() + " --bmi 45 --out " + (dir / "g.obj").string()),
                    out) == 0);
  CHECK_THAT(out, Catch::Contains("warning: the body is outside what model.h5 was trained on: BMI"));
  REQUIRE(test::run(test::drape_command("predict --model " + model.string() + " --bmi 45 --strict --out " +
                                        (dir / "g2.obj").string()),
                    out) == 2);
  CHECK_THAT(out, Catch::Contains("--strict: the body is outside the model's training domain"));
  CHECK(!fs::exists(dir / "g2.obj"));

  // A body inside the domain but standing 2 m up (a mesh placed by another
  // tool) is draped where the training bodies stood and the garment moved
  // back: the prediction for the body with its soles where theirs were (the
  // mean of their lowest y), lifted with the body.
  const auto domain = read_domain(model);
  REQUIRE(domain);
  REQUIRE(domain->placement.allFinite());
  const auto assets = test::tiny_assets();
  Mesh in_place = assets->body;
  in_place.vertices = grown(assets->body.vertices, 1.1);
  in_place.vertices.col(1).array() += domain->placement[1] - in_place.vertices.col(1).minCoeff();
  Mesh lifted = in_place;
  lifted.vertices.col(1).array() += 2.0;
  write_mesh(dir / "in_place.obj", in_place);
  write_mesh(dir / "lifted.obj", lifted);
  REQUIRE(test::run(test::drape_command("predict --model " + model.string() + " --body " + (dir / "in_place.obj").string() +
                                        " --out " + (dir / "g_in_place.obj").string()),
                    out) == 0);
  CHECK_THAT(out, !Catch::Contains("stands"));
  REQUIRE(test::run(test::drape_command("predict --model " + model.string() + " --strict --body " +
                                        (dir / "lifted.obj").string() + " --out " + (dir / "g_lifted.obj").string()),
                    out) == 0);
  CHECK_THAT(out, Catch::Contains("note: the body stands (+0.000, +2.000, +0.000) m from where model.h5's training bodies stood"));
  const Eigen::MatrixX3d a = read_mesh(dir / "g_in_place.obj").vertices, b = read_mesh(dir / "g_lifted.obj").vertices;
  REQUIRE(a.rows() == b.rows());
  CHECK((b.col(1).array() - 2.0 - a.col(1).array()).abs().maxCoeff() < 1e-5);
  CHECK((b.leftCols(1) - a.leftCols(1)).cwiseAbs().maxCoeff() < 1e-6);
  CHECK((b.rightCols(1) - a.rightCols(1)).cwiseAbs().maxCoeff() < 1e-6);
}

TEST_CASE("drape train records the domain of its training split in the model", "[train][domain][cli]") {
  test::TempDir dir;
  const fs::path data = dir / "data.h5", model = dir / "model.h5";
  test::write_tiny_dataset(data, 12, 7, 3);
  std::string out;
  REQUIRE(test::run(test::drape_command("train " + test::baseline_graph().string() + " --data " + data.string() + " --out " +
                                        model.string() + " --epochs 1 --batch 4 --seed 5 --threads 1 --k " +
                                        std::to_string(test::kTinyK)),
                    out) == 0);
  INFO(out);
  CHECK_THAT(out, Catch::Contains("recorded the model's domain: 7 training bodies"));
  const auto domain = read_domain(model);
  REQUIRE(domain);
  CHECK(domain->samples == 7);
  CHECK(domain->source == "data.h5");
  // Still a model drape predict loads, and sealed.
  REQUIRE(test::run(test::drape_command("predict --model " + model.string() + " --bmi 24 --out " + (dir / "g.obj").string()),
                    out) == 0);
  CHECK(h5::File::open(model).is_group("/weights"));
}

TEST_CASE("model domain: a parameter at the edge of the range its bodies were drawn from is inside", "[train][domain]") {
  // 288 heights drawn over 1.50-2.00 m span 1.5022-1.9988 (the shipped body
  // space's first model): the ends fall short of the drawn range by about
  // 0.5 / 289 = 1.7 mm each, so 1.50 and 2.00 m are inside (within five
  // times that, 8.7 mm), 1.49 m is not.
  const auto assets = test::tiny_assets();
  ModelDomain d;
  d.samples = 288;
  d.param_names = {"height"};
  d.params = {ValueRange{1.5022, 1.9988}};
  d.height = {0.0, 10.0};
  d.bmi = {0.0, 1000.0};
  const auto violations = [&](double height) {
    const Eigen::VectorXd params = Eigen::VectorXd::Constant(1, height);
    return domain_violations(d, assets->body.vertices, assets->body.faces, &params);
  };
  CHECK(violations(1.50).empty());
  CHECK(violations(2.00).empty());
  CHECK(violations(1.75).empty());
  const auto low = violations(1.49);
  REQUIRE(low.size() == 1);
  // The range printed to four digits, so that the reader sees why 1.49 is out.
  CHECK_THAT(low.front(), Catch::Contains("shape parameter 'height' 1.49 is outside the trained range 1.502..1.999"));
  // When the measured height is out too, the parameter that is the height says nothing more: one warning, not two.
  {
    ModelDomain tall = d;
    tall.height = {10.0, 20.0};
    const Eigen::VectorXd params = Eigen::VectorXd::Constant(1, 1.49);
    const auto both = domain_violations(tall, assets->body.vertices, assets->body.faces, &params);
    REQUIRE(both.size() == 1);
    CHECK_THAT(both.front(), Catch::StartsWith("height "));
  }

  // The A-pose model of 2,289 bodies: its tallest is 1.99956 m, 0.44 mm
  // short of 2.00, twice the mean shortfall 0.5 / 2290 = 0.22 mm (as likely
  // as exp(-2) = 13.5 %). 2.00 m is inside; 2.002 m (9 mean shortfalls) is not.
  d.samples = 2289;
  d.params = {ValueRange{1.50005, 1.99956}};
  CHECK(violations(2.00).empty());
  CHECK(violations(1.50).empty());
  CHECK(violations(2.002).size() == 1);
}

TEST_CASE("drape model domain refuses a posed set's domain for an A-pose model", "[train][domain][cli]") {
  test::TempDir dir;
  std::string out;
  const std::string model = (test::source_dir() / "models/tshirt-coarse.h5").string();
  CHECK(test::run(test::drape_command("model domain " + model + " --data " +
                                      (test::source_dir() / "datasets/posespace-heldout/heldout-30.h5").string() + " --out " +
                                      (dir / "m.h5").string() + " --force"),
                  out) == 2);
  CHECK_THAT(out, Catch::Contains("heldout-30.h5 holds posed drapes") && Catch::Contains("takes no pose"));
  CHECK_FALSE(fs::exists(dir / "m.h5"));
}

TEST_CASE("a model whose /meta output names no output of its graph is refused naming the file", "[train][model]") {
  // An outside check's edited model failed with exit 1 and "no graph output
  // named 'nosuchnode'", naming no file.
  test::TempDir dir;
  const Model shipped = Model::load(test::plugins(), test::source_dir() / "models/tshirt-coarse.h5");
  Checkpoint c = shipped.checkpoint();
  c.meta["output"] = "nosuchnode";
  Model copy = Model::load(test::plugins(), test::source_dir() / "models/tshirt-coarse.h5");
  save_model_file(dir / "bad.h5", copy.graph().weights(), c, std::nullopt);
  CHECK_THROWS_WITH(Model::load(test::plugins(), dir / "bad.h5"),
                    Catch::Contains("bad.h5: /meta output 'nosuchnode' is no output of its graph"));
}
