// The dataset file: resumable writing that loses or duplicates nothing, even
// when the writer is killed; reading splits; merging shards.
#include <catch2/catch.hpp>

#include "test_support.hpp"

#include <drape/bodies/body.hpp>
#include <drape/io/dataset.hpp>
#include <drape/io/h5.hpp>
#include <drape/warnings.hpp>

#include <algorithm>
#include <csignal>
#include <cmath>
#include <fstream>
#include <sys/wait.h>
#include <unistd.h>

using namespace drape;
using drape::test::TempDir;
using drape::test::message_of;
namespace fs = std::filesystem;

namespace {

DatasetLayout small_layout(std::size_t n = 10) {
  DatasetLayout l;
  l.samples = n;
  l.body_params = 4;
  l.body_vertices = 7;
  l.garment_vertices = 5;
  l.stats = {"energy", "penetration", "seconds"};
  l.scene = "body: { model: parametric }\neffects: [gravity, stretching]\n";
  l.template_hash = "abc123";
  l.attributes = {{"generator", "unit test"}};
  return l;
}

// Every value depends on the sample index and position, so a sample written to
// the wrong row, twice, or half is caught.
float value(std::size_t sample, int array, int k) { return static_cast<float>(sample) * 1000.0f + array * 100.0f + k * 0.25f; }

DatasetSample make_sample(const DatasetLayout& l, std::size_t i) {
  DatasetSample s;
  s.body_params.resize(l.body_params);
  for (int k = 0; k < l.body_params; ++k) s.body_params[k] = value(i, 0, k);
  s.body_vertices.resize(l.body_vertices, 3);
  for (int k = 0; k < l.body_vertices * 3; ++k) s.body_vertices.data()[k] = value(i, 1, k);
  s.garment_vertices.resize(l.garment_vertices, 3);
  for (int k = 0; k < l.garment_vertices * 3; ++k) s.garment_vertices.data()[k] = value(i, 2, k);
  s.split = static_cast<Split>(i % 3);
  s.stats = {{"energy", 0.5 * static_cast<double>(i)}, {"seconds", 1.0 + static_cast<double>(i)}};  // penetration absent
  return s;
}

// A finished shard of layout.samples samples, the k-th made by make(layout, first + k).
template <class Make>
void write_shard(const fs::path& path, const DatasetLayout& layout, std::size_t first, Make make) {
  DatasetWriter w(path, layout);
  for (std::size_t i = 0; i < layout.samples; ++i) w.write(i, make(layout, first + i));
  w.finish();
}

void check_sample(const DatasetReader& reader, std::size_t i) {
  const DatasetSample want = make_sample(reader.layout(), i);
  const DatasetSample got = reader.sample(i);
  CHECK(got.body_params == want.body_params);
  CHECK(got.body_vertices == want.body_vertices);
  CHECK(got.garment_vertices == want.garment_vertices);
  CHECK(got.split == want.split);
  CHECK(got.stats.at("energy") == want.stats.at("energy"));
  CHECK(got.stats.at("seconds") == want.stats.at("seconds"));
  CHECK(std::isnan(got.stats.at("penetration")));
}

void check_complete(const fs::path& path, std::size_t n) {
  const DatasetReader reader(path);
  REQUIRE(reader.size() == n);
  CHECK(reader.indices().size() == n);
  for (std::size_t i = 0; i < n; ++i) check_sample(reader, i);
}

}  // namespace

TEST_CASE("dataset: resume after an unfinished run loses and duplicates nothing", "[hdf5][dataset]") {
  TempDir dir;
  const fs::path out = dir / "data.h5";
  const fs::path partial = DatasetWriter::partial_path(out);
  const DatasetLayout layout = small_layout();
  {
    DatasetWriter writer(out, layout);
    CHECK_FALSE(writer.resumed());
    CHECK(writer.missing().size() == 10);
    for (std::size_t i : {0, 1, 2, 3, 5}) writer.write(i, make_sample(layout, i));
    writer.write(2, make_sample(layout, 2));  // rewriting keeps one copy
    CHECK(fs::exists(partial));
    CHECK_FALSE(fs::exists(out));
    CHECK_THROWS_AS(writer.finish(), Error);
    // Closed unfinished, as if the process stopped here.
  }
  {
    // A torn sample: its arrays were being written when the process died, so
    // `done` was never set. It must count as missing and be rewritten.
    auto file = h5::File::open(partial, h5::Access::ReadWrite);
    const std::vector<float> garbage(layout.garment_vertices * 3, -7.0f);
    file.write_rows("/garments/vertices", 7, 1, garbage.data());
  }
  {
    DatasetLayout again = layout;
    // Another generator (how the samples are made: a seed, a model) would fill
    // the missing rows with other samples: refused, the partial file kept.
    again.attributes = {{"generator", "second run"}};
    CHECK_THROWS_WITH(DatasetWriter(out, again), Catch::Contains("cannot resume, it was begun as \"unit test\" and this "
                                                                 "run asks \"second run\""));
    again.attributes = {{"generator", "unit test"}, {"note", "second run"}};  // other extras are kept from the first run
    DatasetWriter writer(out, again);
    CHECK(writer.resumed());
    CHECK(writer.missing() == std::vector<std::size_t>{4, 6, 7, 8, 9});
    CHECK(writer.done_count() == 5);
    for (std::size_t i : writer.missing()) writer.write(i, make_sample(layout, i));
    CHECK(writer.missing().empty());
    writer.finish();
  }
  CHECK_FALSE(fs::exists(partial));
  check_complete(out, 10);
  const DatasetReader reader(out);
  CHECK(reader.layout().attributes.at("generator") == "unit test");
  CHECK(reader.layout().scene == layout.scene);
  CHECK(reader.layout().template_hash == "abc123");
  CHECK(reader.layout().drape_version == "0.1.0");
  CHECK(reader.layout().created.size() == 20);  // 2024-05-01T12:00:00Z
  // A finished dataset is never overwritten.
  CHECK_THROWS_AS(DatasetWriter(out, layout), ConfigError);
}

TEST_CASE("dataset: a writer killed with SIGKILL at an arbitrary moment resumes cleanly", "[hdf5][dataset]") {
  TempDir dir;
  const fs::path out = dir / "killed.h5";
  const DatasetLayout layout = small_layout(40);
  int pipe_fds[2];
  REQUIRE(::pipe(pipe_fds) == 0);
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    // The child writes samples and reports each one; it gets killed by the
    // parent while it is writing a later one (or in between).
    ::close(pipe_fds[0]);
    try {
      DatasetWriter writer(out, layout);
      for (std::size_t i = 0; i < layout.samples; ++i) {
        writer.write(i, make_sample(layout, i));
        const char c = 'x';
        if (::write(pipe_fds[1], &c, 1) != 1) ::_exit(3);
      }
      for (;;) writer.write(layout.samples - 1, make_sample(layout, layout.samples - 1));  // keep writing until killed
    } catch (...) {
      ::_exit(2);
    }
  }
  ::close(pipe_fds[1]);
  char c;
  for (int reported = 0; reported < 5; ++reported) REQUIRE(::read(pipe_fds[0], &c, 1) == 1);
  ::kill(child, SIGKILL);
  int status = 0;
  ::waitpid(child, &status, 0);
  ::close(pipe_fds[0]);
  REQUIRE(WIFSIGNALED(status));

  DatasetWriter writer(out, layout);
  REQUIRE(writer.resumed());
  const std::size_t survived = writer.done_count();
  CHECK(survived >= 5);  // every reported sample was flushed before it was reported
  {
    // What survived the kill is exact.
    const DatasetReader partial(DatasetWriter::partial_path(out));
    for (std::size_t i : partial.indices()) check_sample(partial, i);
  }
  for (std::size_t i : writer.missing()) writer.write(i, make_sample(layout, i));
  writer.finish();
  check_complete(out, layout.samples);
}

TEST_CASE("dataset: resuming with another layout or a damaged partial file is refused clearly", "[hdf5][dataset]") {
  TempDir dir;
  const fs::path out = dir / "data.h5";
  const fs::path partial = DatasetWriter::partial_path(out);
  const DatasetLayout layout = small_layout();
  DatasetWriter(out, layout).write(0, make_sample(layout, 0));

  DatasetLayout other = layout;
  other.garment_vertices = 6;
  CHECK(message_of([&] { DatasetWriter(out, other); }) ==
        partial.string() + ": cannot resume, garment_vertices is 5 in the file, 6 now; delete it to start over");
  other = layout;
  other.template_hash = "def";
  CHECK_THROWS_WITH(DatasetWriter(out, other), Catch::Contains("template_hash is 'abc123' in the file, 'def' now"));
  other = layout;
  other.garment_vertices = 6;  // another garment: not one dataset with the others
  CHECK_THROWS_AS(DatasetWriter(out, other), ConfigError);
  other = layout;
  other.scene += "# changed\n";
  CHECK_THROWS_WITH(DatasetWriter(out, other), Catch::Contains("the scene YAML differs"));
  // The message names the first line that differs, as each side has it.
  const auto scene_lines = std::count(layout.scene.begin(), layout.scene.end(), '\n');
  CHECK_THROWS_WITH(DatasetWriter(out, other),
                    Catch::Contains("line " + std::to_string(scene_lines + 1) + " is '(the end)' in the file, '# changed' now"));
  other = layout;
  other.scene.insert(0, "solver: {settle_steps: 120}\n");
  CHECK_THROWS_WITH(DatasetWriter(out, other), Catch::Contains("line 1 is '"));
  CHECK_THROWS_WITH(DatasetWriter(out, other), Catch::Contains("' in the file, 'solver: {settle_steps: 120}' now"));

  // A sample of the wrong size is the caller's bug: Error naming the array.
  DatasetWriter writer(out, layout);
  DatasetSample bad = make_sample(layout, 1);
  bad.garment_vertices.resize(4, 3);
  CHECK_THROWS_WITH(writer.write(1, bad), Catch::Contains("sample 1: garment_vertices is [4, 3], the dataset holds [5, 3]"));
  bad = make_sample(layout, 1);
  bad.stats["energie"] = 1.0;
  CHECK_THROWS_WITH(writer.write(1, bad), Catch::Contains("did you mean 'energy'"));
  CHECK_THROWS_AS(writer.write(10, make_sample(layout, 0)), Error);
  writer.close();

  std::ofstream(partial, std::ios::trunc) << "garbage";
  CHECK(message_of([&] { DatasetWriter(out, layout); }) ==
        partial.string() + ": not an HDF5 file; cannot resume from it, delete it to start over");
  CHECK_THROWS_AS(DatasetWriter(out, layout), ConfigError);
}

TEST_CASE("dataset: reading splits and gathering rows in the order asked", "[hdf5][dataset]") {
  TempDir dir;
  const fs::path out = dir / "data.h5";
  const DatasetLayout layout = small_layout(9);
  {
    DatasetWriter writer(out, layout);
    for (std::size_t i = 0; i < 9; ++i)
      if (i != 4) writer.write(i, make_sample(layout, i));
  }
  const DatasetReader reader(DatasetWriter::partial_path(out));
  CHECK(reader.indices(Split::Train) == std::vector<std::size_t>{0, 3, 6});
  CHECK(reader.indices(Split::Val) == std::vector<std::size_t>{1, 7});  // 4 is not done
  CHECK(reader.indices(Split::Test) == std::vector<std::size_t>{2, 5, 8});
  CHECK(reader.indices("train,val") == std::vector<std::size_t>{0, 1, 3, 6, 7});
  CHECK(reader.indices("test") == reader.indices(Split::Test));
  CHECK(reader.indices("all") == reader.indices());
  CHECK_THROWS_WITH(reader.indices("train,tset"), Catch::Contains("unknown split 'tset'"));
  CHECK_THROWS_WITH(reader.indices("Test"), Catch::Contains("did you mean 'test'"));
  // The finished name of a file still partial: said so, not "no such file" alone.
  CHECK_THROWS_WITH(DatasetReader(out), Catch::Contains("data.h5.partial is there") && Catch::Contains("still running or interrupted"));
  CHECK_THROWS_AS(DatasetReader::check_splits("train,"), ConfigError);
  const std::vector<std::size_t> order = {8, 2, 3, 5, 6};
  const Tensor garments = reader.garment_vertices(order);
  REQUIRE(garments.batch() == 5);
  REQUIRE(garments.shape() == Shape{5, 3});
  const Tensor params = reader.body_params(order);
  REQUIRE(params.shape() == Shape{1, 4});
  const Tensor bodies = reader.body_vertices(order);
  for (std::size_t b = 0; b < order.size(); ++b) {
    for (int k = 0; k < 15; ++k) CHECK(garments.data()[b * 15 + k] == value(order[b], 2, k));
    for (int k = 0; k < 21; ++k) CHECK(bodies.data()[b * 21 + k] == value(order[b], 1, k));
    for (int k = 0; k < 4; ++k) CHECK(params(static_cast<int>(b), 0, k) == value(order[b], 0, k));
  }
  CHECK(reader.stat("energy", {3, 1}) == std::vector<double>{1.5, 0.5});
  CHECK_THROWS_WITH(reader.body_params({4}), Catch::Contains("sample 4 was never written completely"));
  CHECK_THROWS_WITH(reader.stat("energi", {0}), Catch::Contains("did you mean 'energy'"));
  CHECK(parse_split("val") == Split::Val);
  CHECK_THROWS_AS(parse_split("validation"), ConfigError);
  // A list of splits also takes `all`, and its refusal says so (it said "expected train, val or test").
  CHECK_THROWS_WITH(DatasetReader::check_splits("train,tst"),
                    Catch::Contains("unknown split 'tst'") && Catch::Contains("did you mean 'test'") &&
                        Catch::Contains("joins train, val and test with commas, or is all"));
  CHECK_NOTHROW(DatasetReader::check_splits("all"));
}

TEST_CASE("dataset: merging shards concatenates their samples", "[hdf5][dataset]") {
  TempDir dir;
  const DatasetLayout a = small_layout(4), b = small_layout(3);
  // Shard b's samples continue a's numbering: sample k of b is global sample 4 + k.
  write_shard(dir / "a.h5", a, 0, make_sample);
  write_shard(dir / "b.h5", b, 4, make_sample);
  CHECK(merge_datasets({dir / "a.h5", dir / "b.h5"}, dir / "all.h5") == 7);
  check_complete(dir / "all.h5", 7);
  CHECK(DatasetReader(dir / "all.h5").layout().attributes.at("merged_from") == "a.h5\nb.h5");

  // An unfinished shard, or one from another template, is refused.
  {
    DatasetWriter w(dir / "c.h5", a);
    w.write(0, make_sample(a, 0));
  }
  const fs::path c = DatasetWriter::partial_path(dir / "c.h5");
  CHECK_THROWS_WITH(merge_datasets({dir / "a.h5", c}, dir / "bad.h5"), Catch::Contains("only 1 of 4 samples are done"));
  CHECK(merge_datasets({dir / "a.h5", c}, dir / "some.h5", false) == 5);
  DatasetLayout other = small_layout(2);
  other.template_hash = "zzz";
  {
    DatasetWriter w(dir / "d.h5", other);
    for (std::size_t i = 0; i < 2; ++i) w.write(i, make_sample(other, i));
    w.finish();
  }
  CHECK_THROWS_AS(merge_datasets({dir / "a.h5", dir / "d.h5"}, dir / "bad.h5"), ConfigError);
  CHECK_FALSE(fs::exists(dir / "bad.h5"));
}

TEST_CASE("dataset: --drop leaves out the samples of the named global indices, and the output lists them", "[hdf5][dataset]") {
  TempDir dir;
  // Two shards of a draw numbered as drape generate numbers it: a's rows are
  // global samples 10-13, b's 14-16 (global_index written by hand here).
  DatasetLayout a = small_layout(4), b = small_layout(3);
  a.stats.push_back("global_index");
  b.stats.push_back("global_index");
  const auto numbered = [](const DatasetLayout& l, std::size_t i) {
    DatasetSample s = make_sample(l, i);
    s.stats["global_index"] = 10.0 + static_cast<double>(i);
    return s;
  };
  write_shard(dir / "a.h5", a, 0, numbered);
  write_shard(dir / "b.h5", b, 4, numbered);
  // Global 11 (a's row 1) and 16 (b's last row) out: five samples, the others in order.
  REQUIRE(merge_datasets({dir / "a.h5", dir / "b.h5"}, dir / "all.h5", true, false, {16, 11}) == 5);
  {
    const DatasetReader all(dir / "all.h5");
    REQUIRE(all.size() == 5);
    const std::vector<std::size_t> kept = {0, 2, 3, 4, 5};  // the make_sample numbers left
    for (std::size_t r = 0; r < kept.size(); ++r) {
      const DatasetSample got = all.sample(r);
      CHECK(got.garment_vertices == make_sample(a, kept[r]).garment_vertices);
      CHECK(got.stats.at("global_index") == 10.0 + static_cast<double>(kept[r]));
    }
    CHECK(all.layout().attributes.at("dropped") == "11,16");
  }
  // A slim copy with one more dropped keeps the list, and a merge of it adds to it.
  REQUIRE(slim_dataset(dir / "a.h5", dir / "a-slim.h5", {12}) == 3);
  CHECK(DatasetReader(dir / "a-slim.h5").layout().attributes.at("dropped") == "12");
  REQUIRE(merge_datasets({dir / "all.h5"}, dir / "again.h5", true, false, {10}) == 4);
  CHECK(DatasetReader(dir / "again.h5").layout().attributes.at("dropped") == "10,11,16");
  // Without --drop, nothing is listed.
  REQUIRE(merge_datasets({dir / "a.h5"}, dir / "plain.h5") == 4);
  CHECK(DatasetReader(dir / "plain.h5").layout().attributes.count("dropped") == 0);

  // An index no shard holds is refused, naming it; so is a shard that cannot tell its samples apart.
  CHECK_THROWS_WITH(merge_datasets({dir / "a.h5", dir / "b.h5"}, dir / "bad.h5", true, false, {17}),
                    Catch::Contains("--drop 17") && Catch::Contains("global index"));
  write_shard(dir / "plain-shard.h5", small_layout(2), 0, make_sample);
  CHECK_THROWS_WITH(slim_dataset(dir / "plain-shard.h5", dir / "bad.h5", {0}), Catch::Contains("no global_index statistic"));
  CHECK_FALSE(fs::exists(dir / "bad.h5"));
}

TEST_CASE("dataset: a shard made before garment_size was recorded merges with its scene's size", "[hdf5][dataset]") {
  TempDir dir;
  DatasetLayout old = small_layout(3);  // no garment_size statistic: a regular shirt by its scene
  old.scene = "garment: {template: tshirt, params: {resolution: coarse, size: regular}}\n";
  DatasetLayout small = small_layout(2);
  small.stats = {"energy", "garment_size", "penetration", "seconds"};
  small.scene = "garment: {template: tshirt, params: {resolution: coarse, size: small}}\n";
  small.template_hash = "def456";
  {
    DatasetWriter w(dir / "old.h5", old);
    for (std::size_t i = 0; i < 3; ++i) w.write(i, make_sample(old, i));
    w.finish();
    DatasetWriter v(dir / "small.h5", small);
    for (std::size_t i = 0; i < 2; ++i) {
      DatasetSample s = make_sample(small, 3 + i);
      s.stats["garment_size"] = 1.0;
      v.write(i, s);
    }
    v.finish();
  }
  // Without --mixed-sizes the templates still differ.
  CHECK_THROWS_AS(merge_datasets({dir / "old.h5", dir / "small.h5"}, dir / "bad.h5"), ConfigError);
  REQUIRE(merge_datasets({dir / "old.h5", dir / "small.h5"}, dir / "both.h5", true, true) == 5);
  const DatasetReader both(dir / "both.h5");
  CHECK(both.layout().has_stat("garment_size"));
  CHECK(both.stat("garment_size", {0, 1, 2, 3, 4}) == std::vector<double>{0, 0, 0, 1, 1});
  CHECK(both.stat("energy", {0, 4}) == std::vector<double>{0.0, 0.5 * 4});

  // A stored scene whose size no flag knows is refused with the shard's name.
  DatasetLayout odd = old;
  odd.scene = "garment: {template: tshirt, params: {size: medium}}\n";
  {
    DatasetWriter w(dir / "odd.h5", odd);
    for (std::size_t i = 0; i < 3; ++i) w.write(i, make_sample(odd, i));
    w.finish();
  }
  CHECK_THROWS_WITH(merge_datasets({dir / "odd.h5", dir / "small.h5"}, dir / "bad.h5", true, true),
                    Catch::Contains("odd.h5") && Catch::Contains("medium"));
}

namespace {

// A body model whose vertices are a known function of the 4 parameters, so an
// expanded dataset's bodies can be checked against it.
class FormulaBody : public BodyModel {
 public:
  // nudge: vertex `nudged` moved that far in x, as a body model changed
  // after a dataset was made would move it.
  explicit FormulaBody(int vertices = 7, double nudge = 0, int nudged = 0)
      : faces_(0, 3), vertices_(vertices), nudge_(nudge), nudged_(nudged) {}
  int num_vertices() const override { return vertices_; }
  const Eigen::MatrixX3i& faces() const override { return faces_; }
  std::vector<std::string> shape_names() const override { return {"a", "b", "c", "d"}; }
  Eigen::VectorXd mean_shape() const override { return Eigen::VectorXd::Zero(4); }
  Eigen::MatrixX3d vertices(const Eigen::VectorXd& shape) const override {
    Eigen::MatrixX3d v(vertices_, 3);
    for (int i = 0; i < vertices_; ++i)
      for (int c = 0; c < 3; ++c) v(i, c) = shape[(i + c) % 4] * (i + 1) + 0.5 * c;
    v(nudged_, 0) += nudge_;
    return v;
  }
  Eigen::VectorXd solve(const BodyRequest&) const override { return mean_shape(); }
  std::pair<double, double> bmi_range() const override { return {10, 65}; }

 private:
  Eigen::MatrixX3i faces_;
  int vertices_;
  double nudge_;
  int nudged_;
};

// make_sample with the body the formula gives for its parameters.
DatasetSample formula_sample(const DatasetLayout& l, std::size_t i) {
  DatasetSample s = make_sample(l, i);
  s.body_vertices = FormulaBody().vertices(s.body_params.cast<double>()).cast<float>();
  return s;
}

}  // namespace

TEST_CASE("dataset: a slim copy leaves the bodies out and expand rebuilds them from the parameters", "[hdf5][dataset]") {
  TempDir dir;
  const DatasetLayout l = small_layout(5);
  {
    DatasetWriter w(dir / "full.h5", l);
    for (std::size_t i = 0; i < 5; ++i) w.write(i, formula_sample(l, i));
    w.finish();
  }
  REQUIRE(slim_dataset(dir / "full.h5", dir / "slim.h5") == 5);
  {
    const DatasetReader slim(dir / "slim.h5");
    CHECK_FALSE(slim.layout().body_vertices_stored);
    CHECK(slim.layout().body_vertices == 7);  // still recorded
    CHECK_FALSE(h5::File::open(dir / "slim.h5").exists("/bodies/vertices"));
    const DatasetSample want = formula_sample(l, 3);
    CHECK(slim.garment_vertices({3}).mat(0) == want.garment_vertices);
    CHECK(slim.stat("energy", {3})[0] == want.stats.at("energy"));
    CHECK(slim.splits() == DatasetReader(dir / "full.h5").splits());
    // Bodies are rebuilt by the stored scene's body model: here not the one that made them (7 vertices), so
    // reading them names the file and both counts, not zeros.
    CHECK_THROWS_WITH(slim.body_vertices({0}), Catch::Contains("slim.h5") && Catch::Contains("7 vertices"));
  }
  CHECK_THROWS_WITH(slim_dataset(dir / "slim.h5", dir / "again.h5"), Catch::Contains("slim dataset already"));
  // A plain merge does not turn a slim shard into a full dataset without bodies.
  CHECK_THROWS_WITH(merge_datasets({dir / "slim.h5"}, dir / "bad.h5"), Catch::Contains("drape dataset expand"));

  // Expanded, slim and full shards join; every body equals the formula's.
  REQUIRE(expand_datasets({dir / "slim.h5", dir / "full.h5"}, dir / "expanded.h5", FormulaBody()) == 10);
  const DatasetReader expanded(dir / "expanded.h5");
  CHECK(expanded.layout().body_vertices_stored);
  for (std::size_t i = 0; i < 10; ++i) {
    const DatasetSample want = formula_sample(l, i % 5);
    const DatasetSample got = expanded.sample(i);
    CHECK(got.body_vertices == want.body_vertices);
    CHECK(got.garment_vertices == want.garment_vertices);
    CHECK(got.body_params == want.body_params);
  }
  // Another body model (another vertex count) is refused, naming both counts.
  CHECK_THROWS_WITH(expand_datasets({dir / "slim.h5"}, dir / "bad.h5", FormulaBody(9)),
                    Catch::Contains("7 vertices") && Catch::Contains("has 9"));
  CHECK_FALSE(fs::exists(dir / "bad.h5"));

  // The slim file keeps a witness of each body left out (here 7 blocks of one
  // vertex: the vertex itself, spread 0), and a body model that no longer
  // builds those bodies is refused as it rebuilds them, naming the sample;
  // within the float rounding it is the same body.
  {
    const h5::File slim = h5::File::open(dir / "slim.h5");
    h5::Dims dims;
    const std::vector<double> witness = slim.read<double>("/bodies/witness", &dims);
    REQUIRE(dims == h5::Dims{5, 7, 4});
    const DatasetSample three = formula_sample(l, 3);
    for (int c = 0; c < 3; ++c) CHECK(witness[(3 * 7 + 2) * 4 + c] == Approx(three.body_vertices(2, c)));
    CHECK(witness[(3 * 7 + 2) * 4 + 3] == 0.0);
  }
  CHECK(DatasetReader(dir / "slim.h5").witnessed_files() == 1);
  CHECK(DatasetReader(dir / "full.h5").witnessed_files() == 0);  // its bodies are stored: nothing to check
  CHECK_THROWS_WITH(expand_datasets({dir / "slim.h5"}, dir / "bad.h5", FormulaBody(7, 0.002, 4)),
                    Catch::Contains("slim.h5") && Catch::Contains("sample 0's body") &&
                        Catch::Contains("not the body its drape was simulated on") && Catch::Contains("vertices 4-4 moved 2.00 mm"));
  CHECK_FALSE(fs::exists(dir / "bad.h5"));
  CHECK(expand_datasets({dir / "slim.h5"}, dir / "close.h5", FormulaBody(7, 1e-5, 4)) == 5);

  // A slim file whose recorded vertex count is damaged is refused, naming it.
  fs::copy_file(dir / "slim.h5", dir / "odd.h5");
  h5::File::open(dir / "odd.h5", h5::Access::ReadWrite).set_attribute("/", "body_vertices_omitted", "7x");
  CHECK_THROWS_WITH(DatasetReader(dir / "odd.h5"), Catch::Contains("odd.h5") && Catch::Contains("'7x', expected a vertex count"));
}

TEST_CASE("dataset: a glob pattern reads its files as one with their faces", "[hdf5][dataset]") {
  TempDir dir;
  DatasetLayout l = small_layout(3);
  l.garment_faces.resize(2, 3);
  l.garment_faces << 0, 1, 2, 2, 3, 4;
  for (const char* name : {"part-0.h5", "part-1.h5"}) {
    DatasetWriter w(dir / name, l);
    for (std::size_t i = 0; i < 3; ++i) w.write(i, make_sample(l, i + (name[5] == '1' ? 3 : 0)));
    w.finish();
  }
  const DatasetReader all((dir / "part-*.h5").string());
  REQUIRE(all.files().size() == 2);
  CHECK(all.size() == 6);
  CHECK(all.layout().garment_faces == l.garment_faces);
  CHECK(all.indices().size() == 6);
  for (std::size_t i = 0; i < 6; ++i) CHECK(all.sample(i).garment_vertices == make_sample(l, i).garment_vertices);
  // Two rows across the files' boundary in one read.
  CHECK(all.garment_vertices({2, 3}).mat(1) == make_sample(l, 3).garment_vertices);
  // drape's lock files match a wide pattern too ('part-0.h5*'), and are no dataset: passed over.
  std::ofstream(dir / "part-0.h5.lock") << "pid 1, drape generate\n";
  CHECK(DatasetReader((dir / "part-0.h5*").string()).files().size() == 1);

  DatasetLayout other = small_layout(3);
  other.garment_vertices = 6;  // another garment: not one dataset with the others
  {
    DatasetWriter w(dir / "part-2.h5", other);
    for (std::size_t i = 0; i < 3; ++i) w.write(i, make_sample(other, i));
    w.finish();
  }
  CHECK_THROWS_WITH(DatasetReader((dir / "part-*.h5").string()), Catch::Contains("part-2.h5") && Catch::Contains("garment_vertices is 5"));
  CHECK_THROWS_WITH(DatasetReader((dir / "none-*.h5").string()), Catch::Contains("no dataset file matches"));
}

namespace {

// A run killed after writing samples 0, 1 and 2 of `layout`: its .partial file.
void write_first_three(const fs::path& out, const DatasetLayout& layout) {
  DatasetWriter writer(out, layout);
  for (std::size_t i : {0, 1, 2}) writer.write(i, make_sample(layout, i));
}

}  // namespace

TEST_CASE("dataset: a resumed run makes again a kept sample that no longer reads back as written", "[hdf5][dataset]") {
  // An outside check flipped bytes in a .partial's garment rows: the resume
  // kept them, and the finished file, sealed, held a vertex at 158 m.
  TempDir dir;
  const fs::path out = dir / "data.h5";
  const DatasetLayout layout = small_layout(5);
  write_first_three(out, layout);  // a run killed after three samples
  {
    auto file = h5::File::open(DatasetWriter::partial_path(out), h5::Access::ReadWrite);
    std::vector<float> row(layout.garment_vertices * 3);
    file.read_rows("/garments/vertices", 1, 1, row.data());
    row[4] = 158.3f;
    file.write_rows("/garments/vertices", 1, 1, row.data());
  }
  std::vector<std::string> warnings;
  const WarningHandler before = set_warning_handler([&](const std::string& text) { warnings.push_back(text); });
  {
    DatasetWriter writer(out, layout);
    set_warning_handler(before);
    CHECK(writer.resumed());
    CHECK(writer.missing() == std::vector<std::size_t>{1, 3, 4});
    REQUIRE(warnings.size() == 1);
    CHECK_THAT(warnings[0], Catch::Contains("1 of the samples the interrupted run wrote no longer read back as written") &&
                                Catch::Contains("sample 1)") && Catch::Contains("made again"));
    for (std::size_t i : writer.missing()) writer.write(i, make_sample(layout, i));
    writer.finish();
  }
  set_warning_handler(before);
  check_complete(out, 5);
  // Untouched, a resume keeps every sample and says nothing.
  warnings.clear();
  {
    DatasetWriter writer(dir / "clean.h5", layout);
    for (std::size_t i : {0, 1}) writer.write(i, make_sample(layout, i));
  }
  set_warning_handler([&](const std::string& text) { warnings.push_back(text); });
  const DatasetWriter writer(dir / "clean.h5", layout);
  set_warning_handler(before);
  CHECK(writer.missing() == std::vector<std::size_t>{2, 3, 4});
  CHECK(warnings.empty());
}

TEST_CASE("dataset: a sample flagged done that was never written is made by the resume", "[hdf5][dataset]") {
  // An outside check set one bit of a killed run's /done: the resume kept an
  // all-zero drape with NaN statistics and sealed it into a complete file.
  TempDir dir;
  const fs::path out = dir / "data.h5";
  const DatasetLayout layout = small_layout(5);
  write_first_three(out, layout);  // a run killed after three samples
  {
    auto file = h5::File::open(DatasetWriter::partial_path(out), h5::Access::ReadWrite);
    const std::uint8_t done = 1;
    file.write_rows("/done", 3, 1, &done);
  }
  std::vector<std::string> warnings;
  const WarningHandler before = set_warning_handler([&](const std::string& text) { warnings.push_back(text); });
  {
    DatasetWriter writer(out, layout);
    set_warning_handler(before);
    CHECK(writer.missing() == std::vector<std::size_t>{3, 4});
    REQUIRE(warnings.size() == 1);
    CHECK_THAT(warnings[0], Catch::Contains("sample 3)"));
    for (std::size_t i : writer.missing()) writer.write(i, make_sample(layout, i));
    writer.finish();
  }
  set_warning_handler(before);
  check_complete(out, 5);
  const DatasetReader reader(out);
  CHECK(reader.garment_vertices({3}).mat(0).isApprox(make_sample(layout, 3).garment_vertices));
}

TEST_CASE("dataset: merging says when one run's drapes go in twice, and which shards of a run are missing", "[hdf5][dataset]") {
  TempDir dir;
  const auto shard_layout = [](const std::string& run, int index, int count) {
    DatasetLayout l = small_layout(2);
    l.attributes = {{"generator", "drape generate: " + run + ", shard " + std::to_string(index) + "/" + std::to_string(count)}};
    return l;
  };
  write_shard(dir / "s0.h5", shard_layout("seed 0, count 4", 0, 2), 0, make_sample);
  write_shard(dir / "s1.h5", shard_layout("seed 0, count 4", 1, 2), 2, make_sample);
  write_shard(dir / "again0.h5", shard_layout("seed 0, count 4", 0, 2), 0, make_sample);
  write_shard(dir / "other.h5", shard_layout("seed 7, count 2", 0, 1), 0, make_sample);
  // The same command in another scene (another size of the garment): another run.
  for (const int index : {0, 1}) {
    DatasetLayout other_scene = shard_layout("seed 0, count 4", index, 2);
    other_scene.scene += "# another size\n";
    write_shard(dir / ("small" + std::to_string(index) + ".h5"), other_scene, 2 * index, make_sample);
  }
  std::vector<std::string> warnings;
  const WarningHandler before = set_warning_handler([&](const std::string& text) { warnings.push_back(text); });
  // The same file twice (oversampling, a use) and the same shard of one run made twice (an outside
  // check merged a full run with a copy of it): merged, and said.
  CHECK(merge_datasets({dir / "s0.h5", dir / "s0.h5", dir / "s1.h5"}, dir / "twice.h5") == 6);
  REQUIRE(warnings.size() == 1);
  CHECK_THAT(warnings[0], Catch::Contains("s0.h5 is given twice") && Catch::Contains("merged twice, each counting twice"));
  warnings.clear();
  CHECK(merge_datasets({dir / "s0.h5", dir / "s1.h5", dir / "again0.h5"}, dir / "again.h5") == 6);
  REQUIRE(warnings.size() == 1);
  CHECK_THAT(warnings[0], Catch::Contains("again0.h5 (shard 0/2) holds drapes of the same run as") &&
                              Catch::Contains("the same drapes are merged twice"));
  // The whole run, and a shard of it in another scene (another size): nothing to say, and the output
  // says which shards it holds.
  warnings.clear();
  CHECK(merge_datasets({dir / "s0.h5", dir / "s1.h5"}, dir / "all.h5") == 4);
  CHECK(merge_datasets({dir / "s0.h5", dir / "s1.h5", dir / "small0.h5", dir / "small1.h5"}, dir / "sizes.h5", true, true) == 8);
  CHECK(warnings.empty());
  CHECK(DatasetReader(dir / "all.h5").layout().attributes.at("generator") == "drape generate: seed 0, count 4, shards 0,1 of 2");
  // A merged file holds its shards too: merged again with one of them (an
  // outside check: 18 rows of 12 drapes, and a warning that shards were
  // missing), the repeat is said, not a lack.
  CHECK(merge_datasets({dir / "all.h5", dir / "s1.h5"}, dir / "repeat.h5") == 6);
  REQUIRE(warnings.size() == 1);
  CHECK_THAT(warnings[0], Catch::Contains("s1.h5 (shard 1/2) holds drapes of the same run as") &&
                              Catch::Contains("(shards 0,1 of 2;") && Catch::Contains("merged twice"));
  warnings.clear();
  // One shard slimmed (one file: a copy, not a merge) lacks nothing, and a
  // copy's "shard 0 of 2" (what a slim copy of shard 0/2 says) is still shard
  // 0 of the run: with shard 1 it is the whole run, with shard 0 a repeat.
  CHECK(slim_dataset(dir / "s0.h5", dir / "s0.slim.h5") == 2);
  CHECK(warnings.empty());
  DatasetLayout copied = shard_layout("seed 0, count 4", 0, 2);
  copied.attributes["generator"] = "drape generate: seed 0, count 4, shard 0 of 2";
  write_shard(dir / "copy0.h5", copied, 0, make_sample);
  CHECK(merge_datasets({dir / "copy0.h5", dir / "s1.h5"}, dir / "whole.h5") == 4);
  CHECK(warnings.empty());
  CHECK(merge_datasets({dir / "s0.h5", dir / "copy0.h5", dir / "s1.h5"}, dir / "copy.h5") == 6);
  REQUIRE(warnings.size() == 1);
  CHECK_THAT(warnings[0], Catch::Contains("copy0.h5 (shard 0/2) holds drapes of the same run as"));
  warnings.clear();
  // Half a run: merged, and told; another run beside it: merged, both named.
  warnings.clear();
  CHECK(merge_datasets({dir / "s0.h5", dir / "other.h5"}, dir / "half.h5") == 4);
  set_warning_handler(before);
  REQUIRE(warnings.size() == 1);
  CHECK_THAT(warnings[0], Catch::Contains("merging shard 0 of the 2 of one run (drape generate: seed 0, count 4)"));
  CHECK(DatasetReader(dir / "half.h5").layout().attributes.at("generator") ==
        "drape generate: seed 0, count 4, shard 0 of 2 + drape generate: seed 7, count 2, shard 0 of 1");
}

TEST_CASE("dataset: a killed run's samples are kept by the resume whatever the order of its statistics", "[hdf5][dataset]") {
  // An outside check: the generator lists its statistics in its own order
  // (energy_gravity, ..., penetration), the file lists them alphabetically,
  // and each sample's checksum was taken in the order of whichever layout
  // the writer had: a resume found every sample of a killed run changed and
  // made them all again. Its finished file had no checksum either.
  TempDir dir;
  const fs::path out = dir / "data.h5";
  DatasetLayout layout = small_layout(5);
  layout.stats = {"seconds", "penetration", "energy"};
  {
    DatasetWriter writer(out, layout);
    for (std::size_t i : {0, 1, 2}) writer.write(i, make_sample(layout, i));
  }  // (closed unfinished; a SIGKILL leaves the same rows, see the test above)
  std::vector<std::string> warnings;
  const WarningHandler before = set_warning_handler([&](const std::string& text) { warnings.push_back(text); });
  {
    DatasetWriter writer(out, layout);
    set_warning_handler(before);
    CHECK(writer.missing() == std::vector<std::size_t>{3, 4});
    writer.write(3, make_sample(layout, 3));
  }
  set_warning_handler([&](const std::string& text) { warnings.push_back(text); });
  {
    DatasetWriter writer(out, layout);  // resumed twice: the second run's sample too
    set_warning_handler(before);
    CHECK(writer.missing() == std::vector<std::size_t>{4});
    writer.write(4, make_sample(layout, 4));
    writer.finish();
  }
  set_warning_handler(before);
  CHECK(warnings.empty());
  check_complete(out, 5);
  // Finished by a resumed writer, the file is sealed as a run's own would be.
  std::ifstream in(out, std::ios::binary);
  std::string head(19, '\0');
  in.read(head.data(), 19);
  CHECK(head == "drape sealed hdf5 1");
}

TEST_CASE("dataset: a NaN in a sample's body or shape parameters is named with its file and sample", "[hdf5][dataset]") {
  // An outside check put a NaN in a body vertex: training ran until "the
  // training loss is nan (try a smaller --lr)"; one in /bodies/params was
  // taken silently into the model's domain.
  TempDir dir;
  const fs::path out = dir / "data.h5";
  const DatasetLayout layout = small_layout(4);
  write_first_three(out, layout);  // a run killed after three samples
  const fs::path partial = DatasetWriter::partial_path(out);
  {
    auto file = h5::File::open(partial, h5::Access::ReadWrite);
    std::vector<float> body(layout.body_vertices * 3), params(layout.body_params);
    file.read_rows("/bodies/vertices", 1, 1, body.data());
    body[10] = std::numeric_limits<float>::quiet_NaN();
    file.write_rows("/bodies/vertices", 1, 1, body.data());
    file.read_rows("/bodies/params", 2, 1, params.data());
    params[0] = std::numeric_limits<float>::infinity();
    file.write_rows("/bodies/params", 2, 1, params.data());
  }
  const DatasetReader reader(partial);
  CHECK_NOTHROW(reader.body_vertices({0, 2}));
  CHECK_NOTHROW(reader.body_params({0, 1}));
  CHECK_THROWS_WITH(reader.body_vertices({0, 1}), Catch::Contains(partial.string() + ": sample 1 has a non-finite body coordinate"));
  CHECK_THROWS_WITH(reader.body_params({2}), Catch::Contains("sample 2 has a non-finite body shape parameter"));
}

TEST_CASE("dataset: a sample whose vertices lie beyond a thousand kilometres or all at the origin is named with its file", "[hdf5][dataset]") {
  // An outside check: a coordinate of 1e30 (an exponent's bit flipped) was
  // trained on to a loss of 1e27; a row marked done but never written (zeros)
  // trained at five times the others' loss and made a potential of inf.
  TempDir dir;
  const fs::path out = dir / "data.h5";
  const DatasetLayout layout = small_layout(4);
  write_first_three(out, layout);
  const fs::path partial = DatasetWriter::partial_path(out);
  {
    auto file = h5::File::open(partial, h5::Access::ReadWrite);
    std::vector<float> garment(layout.garment_vertices * 3), body(layout.body_vertices * 3);
    file.read_rows("/garments/vertices", 1, 1, garment.data());
    garment[4] = 1e30f;
    file.write_rows("/garments/vertices", 1, 1, garment.data());
    std::fill(garment.begin(), garment.end(), 0.0f);
    file.write_rows("/garments/vertices", 2, 1, garment.data());
    file.read_rows("/bodies/vertices", 0, 1, body.data());
    body[7] = -2e7f;
    file.write_rows("/bodies/vertices", 0, 1, body.data());
  }
  const DatasetReader reader(partial);
  CHECK_NOTHROW(reader.garment_vertices({0}));
  CHECK_THROWS_WITH(reader.garment_vertices({1}),
                    Catch::Contains(partial.string() + ": sample 1 has a garment coordinate of 1e+30 m, beyond a thousand kilometres"));
  CHECK_THROWS_WITH(reader.garment_vertices({2}), Catch::Contains("sample 2: every garment vertex is at (0, 0, 0), HDF5's fill value"));
  CHECK_THROWS_WITH(reader.body_vertices({0}), Catch::Contains("sample 0 has a body coordinate of 2e+07 m"));
}

TEST_CASE("dataset: a file that appears at the output while a set is made is not replaced by it", "[hdf5][dataset]") {
  // <out> is never overwritten: checked at the start, it was not at the end, and a model written there meanwhile
  // (by a command that took no lock) was replaced by the finished dataset without a word (an outside check).
  TempDir dir;
  const fs::path out = dir / "data.h5";
  const DatasetLayout layout = small_layout(3);
  DatasetWriter writer(out, layout);
  for (std::size_t i = 0; i < layout.samples; ++i) writer.write(i, make_sample(layout, i));
  std::ofstream(out) << "written meanwhile";
  CHECK_THROWS_WITH(writer.finish(), Catch::Contains("appeared while the dataset was made") &&
                                         Catch::Contains(DatasetWriter::partial_path(out).string()));
  std::ifstream in(out);
  std::string kept;
  std::getline(in, kept);
  CHECK(kept == "written meanwhile");
  check_complete(DatasetWriter::partial_path(out), 3);
}
