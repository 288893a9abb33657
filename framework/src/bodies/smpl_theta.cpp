// SMPL's θ from a file into a Pose (smpl_theta.hpp).
#include <drape/bodies/smpl_theta.hpp>
#include <drape/errors.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <regex>
#include <sstream>

namespace drape {
namespace {

std::string read_all(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw ConfigError("theta file " + file.string() + ": cannot be read");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// NumPy's format (numpy.lib.format): magic, version, header length, a Python
// dict literal {'descr': '<f8', 'fortran_order': False, 'shape': (72,), }, data.
std::vector<double> parse_npy(const std::string& bytes, const std::string& name) {
  const std::string bad = "theta file " + name + ": ";
  if (bytes.size() < 10) throw ConfigError(bad + "too short for a .npy file");
  const int major = static_cast<unsigned char>(bytes[6]);
  const std::size_t len_bytes = major == 1 ? 2 : 4;
  std::size_t header_len = 0;
  for (std::size_t i = 0; i < len_bytes; ++i) header_len |= static_cast<std::size_t>(static_cast<unsigned char>(bytes[8 + i])) << (8 * i);
  const std::size_t data_at = 8 + len_bytes + header_len;
  if (bytes.size() < data_at) throw ConfigError(bad + "its .npy header is cut short");
  const std::string header = bytes.substr(8 + len_bytes, header_len);
  std::smatch m;
  if (!std::regex_search(header, m, std::regex("'descr'\\s*:\\s*'([<|=]?)(f8|f4)'")))
    throw ConfigError(bad + "expected a little-endian float64 or float32 .npy array, the header says " +
                      header.substr(0, header.find_last_not_of(" \n") + 1));  // (numpy pads it with spaces and a newline)
  const bool f8 = m[2] == "f8";
  if (std::regex_search(header, std::regex("'fortran_order'\\s*:\\s*True")) &&
      !std::regex_search(header, std::regex("'shape'\\s*:\\s*\\(\\s*\\d*\\s*,?\\s*\\)")))
    throw ConfigError(bad + "a Fortran-ordered array; save it with numpy.ascontiguousarray");
  if (!std::regex_search(header, m, std::regex("'shape'\\s*:\\s*\\(([^)]*)\\)"))) throw ConfigError(bad + "no shape in the .npy header");
  std::size_t count = 1;
  const std::string dims = m[1];
  const std::regex number("\\d+");
  for (std::sregex_iterator it(dims.begin(), dims.end(), number), end; it != end; ++it) count *= std::stoul(it->str());
  const std::size_t width = f8 ? 8 : 4;
  if (bytes.size() - data_at != count * width)
    throw ConfigError(bad + "holds " + std::to_string(bytes.size() - data_at) + " bytes of data for " + std::to_string(count) +
                      " numbers of " + std::to_string(width) + " bytes");
  std::vector<double> out(count);
  for (std::size_t i = 0; i < count; ++i) {
    if (f8) {
      std::memcpy(&out[i], bytes.data() + data_at + 8 * i, 8);
    } else {
      float v;
      std::memcpy(&v, bytes.data() + data_at + 4 * i, 4);
      out[i] = v;
    }
  }
  return out;
}

std::vector<double> parse_text(const std::string& text, const std::string& name) {
  std::vector<double> out;
  std::istringstream lines(text);
  std::string line;
  for (int at = 1; std::getline(lines, line); ++at) {
    line = line.substr(0, line.find('#'));
    for (char& c : line)
      if (c == ',' || c == '[' || c == ']') c = ' ';
    std::istringstream words(line);
    std::string word;
    while (words >> word) {
      char* end = nullptr;
      const double v = std::strtod(word.c_str(), &end);
      if (end == word.c_str() || *end != '\0')
        throw ConfigError("theta file " + name + ":" + std::to_string(at) + ": '" + word + "' is not a number");
      out.push_back(v);
    }
  }
  return out;
}

}  // namespace

std::vector<double> read_theta_file(const std::filesystem::path& file) {
  const std::string bytes = read_all(file);
  const bool npy = bytes.size() >= 6 && bytes.compare(0, 6, "\x93NUMPY") == 0;
  std::vector<double> theta = npy ? parse_npy(bytes, file.string()) : parse_text(bytes, file.string());
  for (std::size_t i = 0; i < theta.size(); ++i)
    if (!std::isfinite(theta[i]))
      throw ConfigError("theta file " + file.string() + ": number " + std::to_string(i + 1) + " of " + std::to_string(theta.size()) +
                        " is " + (std::isnan(theta[i]) ? "NaN" : "infinite"));
  return theta;
}

Pose pose_from_theta(const std::vector<double>& theta, const BodyModel& model, const std::string& what) {
  const std::vector<BodyModel::Joint> joints = model.joints();
  const std::size_t k = joints.size();
  for (std::size_t j = 0; j < k; ++j) {
    const auto& a = joints[j].angles;
    const bool axis_angle = j == 0 ? a.empty()
                                   : a.size() == 3 && a[0] == joints[j].name + "_x" && a[1] == joints[j].name + "_y" &&
                                         a[2] == joints[j].name + "_z";
    if (!model.poseable() || !axis_angle)
      throw ConfigError(what + ": this body model's joints do not take SMPL's axis-angle theta (the SMPL body model does: "
                        "drape body --model smpl with a file that has its pose datasets, or a model trained on SMPL "
                        "bodies; docs/smpl.md)");
  }
  if (theta.size() != 3 * k && theta.size() != 3 * (k - 1))
    throw ConfigError(what + ": " + std::to_string(theta.size()) + " numbers; SMPL's theta for this model's " + std::to_string(k) +
                      " joints is " + std::to_string(3 * k) + " (one axis-angle vector per joint in radians, the root first) or " +
                      std::to_string(3 * (k - 1)) + " (without the root)");
  for (std::size_t i = 0; i < theta.size(); ++i)
    if (!std::isfinite(theta[i])) throw ConfigError(what + ": number " + std::to_string(i + 1) + " is not finite");
  const std::size_t first = theta.size() == 3 * k ? 3 : 0;  // where joint 1 starts
  if (first == 3 && (theta[0] != 0 || theta[1] != 0 || theta[2] != 0)) {
    std::ostringstream m;
    m << what << ": the root (" << joints[0].name << ") turns by (" << theta[0] << ", " << theta[1] << ", " << theta[2]
      << ") radians; drape's bodies stand upright (gravity -Y), so SMPL's global orientation is not a pose angle: give "
      << 3 * (k - 1) << " numbers, or 0 0 0 first";
    throw ConfigError(m.str());
  }
  Pose pose;
  for (std::size_t j = 1; j < k; ++j) {
    Eigen::Vector3d v(theta[first + 3 * (j - 1)], theta[first + 3 * (j - 1) + 1], theta[first + 3 * (j - 1) + 2]);
    const double angle = v.norm();
    // The same rotation by an angle in (-pi, pi] about the same axis.
    if (angle > M_PI) v *= std::remainder(angle, 2 * M_PI) / angle;
    for (int c = 0; c < 3; ++c) pose.angles[joints[j].angles[static_cast<std::size_t>(c)]] = std::clamp(v[c] * 180.0 / M_PI, -180.0, 180.0);  // pi's rounding
  }
  check_pose(pose, model.pose_angles(), what);
  return pose;
}

}  // namespace drape
