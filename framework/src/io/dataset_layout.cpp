// The dataset file's layout: creating it empty, reading it back, comparing.
#include "dataset_internal.hpp"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <utility>

#include <yaml-cpp/yaml.h>

namespace drape {

bool DatasetLayout::has_stat(const std::string& name) const {
  return std::find(stats.begin(), stats.end(), name) != stats.end();
}

const char* to_string(Split split) {
  switch (split) {
    case Split::Train: return "train";
    case Split::Val: return "val";
    case Split::Test: return "test";
  }
  return "?";
}

Split parse_split(const std::string& name) {
  for (Split s : {Split::Train, Split::Val, Split::Test})
    if (name == to_string(s)) return s;
  throw ConfigError("unknown split '" + name + "' (expected train, val or test)" +
                    did_you_mean(name, {"train", "val", "test"}));
}

namespace dataset_detail {

namespace {

// Root attributes with a meaning of their own; everything else is an extra.
const std::set<std::string> kReserved = {"format", "scene", "template_hash", "drape_version", "created",
                                         kBodyVerticesOmitted, kPoseAngles};

std::size_t to_size(int n) { return static_cast<std::size_t>(n); }

// /garments/faces, checked: [F, 3] indices of the Ng garment vertices.
Eigen::MatrixX3i read_faces(const h5::File& file, int garment_vertices) {
  h5::Dims d;
  const std::vector<std::int32_t> data = file.read<std::int32_t>(kGarmentFaces, &d);
  const std::string name = file.path().string();
  if (d.size() != 2 || d[1] != 3)
    throw ConfigError(name + ": " + kGarmentFaces + " has shape " + h5::to_string(d) + ", expected [F, 3]");
  for (std::int32_t v : data)
    if (v < 0 || v >= garment_vertices)
      throw ConfigError(name + ": " + kGarmentFaces + " holds vertex " + std::to_string(v) + ", not one of the " +
                        std::to_string(garment_vertices) + " garment vertices");
  Eigen::MatrixX3i faces(static_cast<Eigen::Index>(d[0]), 3);
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int c = 0; c < 3; ++c) faces(f, c) = data[static_cast<std::size_t>(f * 3 + c)];
  return faces;
}

// The first line where two scene texts part, quoted from each (cut at 120
// characters): "the scene YAML differs" alone left a user to diff the
// files (a scene read from a working tree that changed between two shards).
std::string first_scene_difference(const std::string& have, const std::string& now, const std::string& have_is,
                                   const std::string& now_is) {
  std::istringstream a(have), b(now);
  std::string la, lb;
  for (int line = 1;; ++line) {
    const bool more_a = static_cast<bool>(std::getline(a, la)), more_b = static_cast<bool>(std::getline(b, lb));
    if (!more_a && !more_b) return "";
    if (!more_a) la = "(the end)";
    if (!more_b) lb = "(the end)";
    if (la != lb || !more_a || !more_b) {
      const auto cut = [](std::string s) { return s.size() > 120 ? s.substr(0, 117) + "..." : s; };
      return ": line " + std::to_string(line) + " is '" + cut(la) + "' " + have_is + ", '" + cut(lb) + "' " + now_is;
    }
  }
}

}  // namespace

std::string now_utc() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buffer;
}

void create_layout(h5::File& file, const DatasetLayout& layout) {
  if (layout.body_params < 0 || layout.body_vertices < 0 || layout.garment_vertices < 0)
    throw Error("dataset layout: negative sizes");
  for (const auto& [name, value] : layout.attributes)
    if (kReserved.count(name)) throw Error("dataset attribute '" + name + "' is reserved; it is set from the layout");
  for (const auto& name : layout.stats)
    if (name.empty() || name.find('/') != std::string::npos)
      throw Error("dataset statistic '" + name + "': names must be non-empty and contain no '/'");
  const std::size_t n = layout.samples;
  // Big arrays: no fill (sparse on disk until written; `done` says what is valid).
  const h5::CreateOptions arrays{.preallocate = true};
  file.create<float>(kParams, {n, to_size(layout.body_params)}, arrays);
  if (layout.body_vertices_stored)
    file.create<float>(kBodyVertices, {n, to_size(layout.body_vertices), 3}, arrays);
  else
    file.set_attribute("/", kBodyVerticesOmitted, std::to_string(layout.body_vertices));
  if (!layout.pose_angles.empty()) {
    std::string names;
    for (const auto& a : layout.pose_angles) {
      if (a.empty() || a.find(',') != std::string::npos) throw Error("dataset pose angle '" + a + "': names must be non-empty without ','");
      names += (names.empty() ? "" : ",") + a;
    }
    file.create<float>(kPose, {n, layout.pose_angles.size()}, arrays);
    file.set_attribute("/", kPoseAngles, names);
  }
  file.create<float>(kGarmentVertices, {n, to_size(layout.garment_vertices), 3}, arrays);
  if (layout.garment_faces.rows() > 0) {
    // Row-major, as h5py and NumPy read it (Eigen's matrix is column-major).
    const Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor> faces = layout.garment_faces;
    file.write<std::int32_t>(kGarmentFaces, {to_size(static_cast<int>(faces.rows())), 3}, faces.data());
  }
  file.create<std::int8_t>(kSplit, {n}, {.preallocate = true, .fill = 0.0});
  file.create<std::uint8_t>(kDone, {n}, {.preallocate = true, .fill = 0.0});
  file.create_group(kStats);
  for (const auto& name : layout.stats) file.create<double>(stat_path(name), {n}, {.preallocate = true, .fill = std::nan("")});
  file.set_attribute("/", "format", kFormat);
  file.set_attribute("/", "scene", layout.scene);
  file.set_attribute("/", "template_hash", layout.template_hash);
  file.set_attribute("/", "drape_version", layout.drape_version);
  file.set_attribute("/", "created", layout.created.empty() ? now_utc() : layout.created);
  for (const auto& [name, value] : layout.attributes) file.set_attribute("/", name, value);
}

DatasetLayout read_layout(const h5::File& file) {
  const std::string name = file.path().string();
  const auto format = file.string_attribute("/", "format");
  if (format && *format != kFormat)
    throw ConfigError(name + ": not a drape dataset (format '" + *format + "', expected '" + kFormat + "')");
  DatasetLayout layout;
  const h5::Dims split = file.shape(kSplit);
  if (split.size() != 1) throw ConfigError(name + ": " + kSplit + " has shape " + h5::to_string(split) + ", expected [N]");
  layout.samples = split[0];
  // The count is /split's; where /split alone disagrees with /done and the
  // garments, /split is named (a short /split blamed the intact /bodies/params:
  // an outside check).
  if (file.exists(kDone) && file.exists(kGarmentVertices)) {
    const h5::Dims done = file.shape(kDone), garments = file.shape(kGarmentVertices);
    if (done.size() == 1 && !garments.empty() && done[0] == garments[0] && done[0] != split[0])
      throw ConfigError(name + ": " + kSplit + " has " + std::to_string(split[0]) + " rows, /done and " + kGarmentVertices +
                        " " + std::to_string(done[0]) + ": the file was edited or is damaged");
  }
  const std::size_t n = layout.samples;
  // Coordinates and parameters are floats (f32; f64 reads the same): an
  // array written as integers (garments in int32 millimetres) was converted
  // without a word and measured as an ME of 1.3e5 cm (an outside check).
  auto expect_type = [&](const char* path, bool floating) {
    const h5::DType t = file.dtype(path);
    const bool is_float = t == h5::DType::F32 || t == h5::DType::F64;
    if (is_float != floating)
      throw ConfigError(name + ": " + path + " holds " + h5::to_string(t) + " values, expected " +
                        (floating ? "floating point (f32)" : "whole numbers (i8 or u8)") +
                        ": the file was edited or is damaged (docs/formats.md lists each array's type)");
  };
  auto expect = [&](const char* path, std::size_t rank, std::size_t last) {
    expect_type(path, true);
    const h5::Dims d = file.shape(path);
    if (d.size() != rank || d[0] != n || (rank == 3 && d[2] != last))
      throw ConfigError(name + ": " + path + " has shape " + h5::to_string(d) + ", expected [" + std::to_string(n) +
                        (rank == 3 ? ", *, 3]" : ", *]"));
    return static_cast<int>(d[1]);
  };
  layout.body_params = expect(kParams, 2, 0);
  if (file.exists(kBodyVertices)) {
    layout.body_vertices = expect(kBodyVertices, 3, 3);
  } else if (const auto omitted = file.string_attribute("/", kBodyVerticesOmitted)) {
    // A slim dataset: the count alone (slim_dataset).
    std::size_t used = 0;
    int count = -1;
    try {
      count = std::stoi(*omitted, &used);
    } catch (const std::exception&) {
    }
    if (count < 0 || used != omitted->size())
      throw ConfigError(name + ": attribute " + kBodyVerticesOmitted + " is '" + *omitted + "', expected a vertex count");
    layout.body_vertices = count;
    layout.body_vertices_stored = false;
  } else {
    throw ConfigError(name + ": missing dataset " + kBodyVertices);
  }
  if (file.exists(kPose)) {
    const auto names = file.string_attribute("/", kPoseAngles);
    if (!names) throw ConfigError(name + ": " + kPose + " has no root attribute " + kPoseAngles + " naming its columns");
    std::stringstream items(*names);
    for (std::string item; std::getline(items, item, ',');) layout.pose_angles.push_back(item);
    const int columns = expect(kPose, 2, 0);
    if (static_cast<std::size_t>(columns) != layout.pose_angles.size())
      throw ConfigError(name + ": " + kPose + " has " + std::to_string(columns) + " columns, its attribute " + kPoseAngles +
                        " names " + std::to_string(layout.pose_angles.size()));
  }
  layout.garment_vertices = expect(kGarmentVertices, 3, 3);
  if (file.exists(kGarmentFaces)) layout.garment_faces = read_faces(file, layout.garment_vertices);
  expect_type(kSplit, false);
  expect_type(kDone, false);
  if (file.shape(kDone) != h5::Dims{n})
    throw ConfigError(name + ": " + kDone + " has shape " + h5::to_string(file.shape(kDone)) + ", expected [" + std::to_string(n) + "]");
  if (file.is_group(kStats)) {
    for (const auto& stat : file.datasets_below(kStats)) {
      if (file.shape(stat_path(stat)) != h5::Dims{n})
        throw ConfigError(name + ": " + stat_path(stat) + " has shape " + h5::to_string(file.shape(stat_path(stat))) +
                          ", expected [" + std::to_string(n) + "]");
      layout.stats.push_back(stat);
    }
  }
  layout.scene = file.require_string_attribute("/", "scene");
  layout.template_hash = file.require_string_attribute("/", "template_hash");
  layout.drape_version = file.require_string_attribute("/", "drape_version");
  layout.created = file.require_string_attribute("/", "created");
  for (const auto& attr : file.attribute_names("/")) {
    if (kReserved.count(attr)) continue;
    if (auto value = file.string_attribute("/", attr)) layout.attributes[attr] = *value;
  }
  return layout;
}

std::string made_difference(const DatasetLayout& have, const DatasetLayout& now) {
  if (std::string difference = layout_difference(have, now); !difference.empty()) return difference;
  const auto begun = have.attributes.find("generator");
  const auto asked = now.attributes.find("generator");
  if (begun != have.attributes.end() && asked != now.attributes.end() && begun->second != asked->second)
    return "it was begun as \"" + begun->second + "\" and this run asks \"" + asked->second + "\"";
  // What the generator names by file only, by content (optimize --data: a
  // model retrained in place, or another dataset of the same file name,
  // resumed into the same output and mixed, an outside check).
  for (const auto& [key, what] : {std::pair{"source_drapes", "the source dataset's drapes"},
                                  std::pair{"model_weights", "the model's weights"}}) {
    const auto a = have.attributes.find(key), b = now.attributes.find(key);
    if (a != have.attributes.end() && b != now.attributes.end() && a->second != b->second)
      return std::string(what) + " differ from the run that began it (fingerprint " + a->second + ", now " + b->second + ")";
  }
  return "";
}

std::optional<std::size_t> finished_by_same_request(const std::string& out, const DatasetLayout& now, const std::string& redo) {
  if (std::error_code ec; !std::filesystem::exists(out, ec)) return std::nullopt;
  const DatasetReader finished(out);
  if (const std::string difference = made_difference(finished.layout(), now); !difference.empty())
    throw ConfigError(out + ": already exists, a finished dataset made otherwise (" + difference + "); delete it to " + redo +
                      ", or give another --out");
  return finished.size();
}

std::string layout_difference(const DatasetLayout& have, const DatasetLayout& now, const std::string& have_is,
                              const std::string& now_is) {
  auto number = [&](const char* what, std::size_t a, std::size_t b) {
    return a == b ? std::string()
                  : std::string(what) + " is " + std::to_string(a) + " " + have_is + ", " + std::to_string(b) + " " + now_is;
  };
  for (const std::string& d : {number("samples", have.samples, now.samples),
                               number("body_params", to_size(have.body_params), to_size(now.body_params)),
                               number("body_vertices", to_size(have.body_vertices), to_size(now.body_vertices)),
                               number("garment_vertices", to_size(have.garment_vertices), to_size(now.garment_vertices))})
    if (!d.empty()) return d;
  if (have.body_vertices_stored != now.body_vertices_stored)
    return std::string("body vertices are ") + (have.body_vertices_stored ? "stored" : "left out (a slim dataset)") +
           " " + have_is + ", " + (now.body_vertices_stored ? "stored" : "left out") + " " + now_is;
  if (have.pose_angles != now.pose_angles) {
    auto list = [](const std::vector<std::string>& v) {
      std::string s;
      for (const auto& a : v) s += (s.empty() ? "" : ",") + a;
      return v.empty() ? std::string("none (A-pose bodies)") : "[" + s + "]";
    };
    return "pose angles are " + list(have.pose_angles) + " " + have_is + ", " + list(now.pose_angles) + " " + now_is;
  }
  auto sorted = [](std::vector<std::string> v) {
    std::sort(v.begin(), v.end());
    return v;
  };
  if (sorted(have.stats) != sorted(now.stats)) {
    std::string a, b;
    for (const auto& s : sorted(have.stats)) a += (a.empty() ? "" : ", ") + s;
    for (const auto& s : sorted(now.stats)) b += (b.empty() ? "" : ", ") + s;
    return "stats are [" + a + "] " + have_is + ", [" + b + "] " + now_is;
  }
  if (have.scene != now.scene) return "the scene YAML differs" + first_scene_difference(have.scene, now.scene, have_is, now_is);
  if (have.template_hash != now.template_hash)
    return "template_hash is '" + have.template_hash + "' " + have_is + ", '" + now.template_hash + "' " + now_is;
  return "";
}

std::string rest_pose_mix_difference(const DatasetLayout& a, const DatasetLayout& b) {
  if (a.pose_angles.empty() == b.pose_angles.empty()) return layout_difference(a, b);
  // The scene without what only says how the body got where it is.
  auto what_is_draped = [](const std::string& yaml) {
    YAML::Node scene = YAML::Load(yaml);
    scene.remove("description");
    scene.remove("solver");
    YAML::Emitter out;
    out << scene;
    return std::string(out.c_str());
  };
  DatasetLayout x = a, y = b;
  x.pose_angles.clear();
  y.pose_angles.clear();
  try {
    x.scene = what_is_draped(a.scene);
    y.scene = what_is_draped(b.scene);
  } catch (const YAML::Exception&) {
    return "a stored scene is not YAML";
  }
  return layout_difference(x, y);
}

void join_size_chart(std::optional<SizeTable>& chart, const DatasetLayout& layout, const std::string& file) {
  const auto text = layout.attributes.find("size_chart");
  if (text == layout.attributes.end()) return;
  const SizeTable read = SizeTable::parse(text->second, file + "'s size_chart");
  try {
    chart = chart ? SizeTable::join(*chart, read) : read;
  } catch (const ConfigError& e) {
    throw ConfigError(file + ": " + e.what() + " from another file's (another garment?)");
  }
}

void check_sample(const DatasetLayout& layout, const DatasetSample& sample, const std::string& where) {
  auto check = [&](const char* what, Eigen::Index rows, Eigen::Index cols, int want_rows, int want_cols) {
    if (rows != want_rows || cols != want_cols)
      throw Error(where + ": " + what + " is [" + std::to_string(rows) + ", " + std::to_string(cols) + "], the dataset holds [" +
                  std::to_string(want_rows) + ", " + std::to_string(want_cols) + "]");
  };
  check("body_params", sample.body_params.size(), 1, layout.body_params, 1);
  check("body_vertices", sample.body_vertices.rows(), sample.body_vertices.cols(), layout.body_vertices, 3);
  check("garment_vertices", sample.garment_vertices.rows(), sample.garment_vertices.cols(), layout.garment_vertices, 3);
  check("pose", sample.pose.size(), 1, static_cast<int>(layout.pose_angles.size()), 1);
  const int split = static_cast<int>(sample.split);
  if (split < 0 || split > 2) throw Error(where + ": split " + std::to_string(split) + " is not 0, 1 or 2");
  for (const auto& [name, value] : sample.stats)
    if (std::find(layout.stats.begin(), layout.stats.end(), name) == layout.stats.end())
      throw Error(where + ": statistic '" + name + "' is not in the dataset's stats" + did_you_mean(name, layout.stats));
}

}  // namespace dataset_detail
}  // namespace drape
