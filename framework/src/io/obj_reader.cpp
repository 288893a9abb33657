// Our own OBJ parser: assimp would reorder the vertices per face corner, and the
// `v` order is the identity of a fixed-topology mesh. One pass over the file held
// in memory with std::from_chars (iostream per token is ~10x slower on the
// 19k-vertex MakeHuman base mesh).
#include <drape/errors.hpp>
#include <drape/io/mesh_io.hpp>

#include "mesh_io_internal.hpp"

#include <charconv>
#include <cmath>
#include <cstring>
#include <string_view>
#include <unordered_map>

namespace drape {
namespace {

class LineCursor {
 public:
  LineCursor(const char* begin, const char* end) : p_(begin), end_(end) {}

  bool at_end() {
    skip_blanks();
    return p_ == end_;
  }
  std::string_view word() {
    skip_blanks();
    const char* start = p_;
    while (p_ != end_ && !is_blank(*p_)) ++p_;
    return {start, static_cast<std::size_t>(p_ - start)};
  }
  std::string_view rest() {
    skip_blanks();
    const char* last = end_;
    while (last != p_ && is_blank(last[-1])) --last;
    return {p_, static_cast<std::size_t>(last - p_)};
  }
  // A number that ends at a blank or the end of the line.
  bool number(double& x) {
    skip_blanks();
    if (p_ != end_ && *p_ == '+') ++p_;  // from_chars rejects a leading '+'
    const auto [ptr, ec] = std::from_chars(p_, end_, x);
    if (ec != std::errc() || (ptr != end_ && !is_blank(*ptr))) return false;
    p_ = ptr;
    return true;
  }
  // One face corner "v", "v/t", "v//n" or "v/t/n"; t = 0 when absent.
  bool corner(long& v, long& t) {
    skip_blanks();
    t = 0;
    if (!integer(v)) return false;
    if (p_ != end_ && *p_ == '/') {
      ++p_;
      if (p_ != end_ && *p_ != '/' && !integer(t)) return false;
      if (p_ != end_ && *p_ == '/') {
        ++p_;
        long n = 0;
        if (!integer(n)) return false;
      }
    }
    return p_ == end_ || is_blank(*p_);
  }

 private:
  static bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }
  void skip_blanks() {
    while (p_ != end_ && is_blank(*p_)) ++p_;
  }
  bool integer(long& x) {
    if (p_ != end_ && *p_ == '+') ++p_;
    const auto [ptr, ec] = std::from_chars(p_, end_, x);
    if (ec != std::errc()) return false;
    p_ = ptr;
    return true;
  }
  const char* p_;
  const char* end_;
};

// Resolves a 1-based (or negative, relative) OBJ index against `count` entries defined so far.
int resolve_index(long index, std::size_t count, const char* kind, const char* kinds, const SourceLocation& where) {
  const long n = static_cast<long>(count);
  const long resolved = index > 0 ? index - 1 : n + index;
  if (index == 0)
    throw ConfigError(where, "face refers to " + std::string(kind) + " 0, which no OBJ index names (they count from 1, or "
                             "back from -1)");
  if (resolved < 0 || resolved >= n)
    throw ConfigError(where, "face refers to " + std::string(kind) + " " + std::to_string(index) + " but " +
                                 std::to_string(n) + " " + (n == 1 ? kind : kinds) + (n == 1 ? " is" : " are") +
                                 " defined before this line");
  return static_cast<int>(resolved);
}

// A face label an OBJ sets by statement (`g`/`o` groups, `usemtl`
// materials): the distinct names in order of first use by a face, and each
// face's index into them ("default" before the first statement).
struct FaceLabels {
  std::vector<std::string>& names;
  std::vector<int>& per_face;
  std::unordered_map<std::string, int> index{};
  std::string current = "default";
  int id = -1;  // looked up when the first face under the current name comes

  void set(std::string_view name) {
    current = name.empty() ? "default" : std::string(name);
    id = -1;
  }
  void label_face() {
    if (id < 0) {
      const auto [it, added] = index.try_emplace(current, static_cast<int>(names.size()));
      if (added) names.push_back(current);
      id = it->second;
    }
    per_face.push_back(id);
  }
};

struct ObjParser {
  std::string path;
  std::vector<double> positions, uvs;
  PolygonMesh out;
  FaceLabels groups{out.group_names, out.face_group};  // refer into `out`: the parser is not copied
  FaceLabels materials{out.material_names, out.face_material};
  int first_face_line = 0;
  bool faces_have_uv = false;

  ObjParser() = default;
  ObjParser(const ObjParser&) = delete;
  ObjParser& operator=(const ObjParser&) = delete;

  void vertex(LineCursor& c, const SourceLocation& where) {
    double x[3];
    for (double& xi : x)
      if (!c.number(xi)) throw ConfigError(where, "'v' needs three numbers x y z");
    for (double xi : x)
      if (!std::isfinite(xi)) throw ConfigError(where, "vertex coordinate is not a finite number");
    positions.insert(positions.end(), x, x + 3);
    // Anything after x y z (w, or r g b vertex colours) is ignored on purpose.
  }

  void texcoord(LineCursor& c, const SourceLocation& where) {
    double t[2];
    for (double& ti : t)
      if (!c.number(ti)) throw ConfigError(where, "'vt' needs two numbers u v");
    for (double ti : t)
      if (!std::isfinite(ti)) throw ConfigError(where, "texture coordinate is not a finite number");
    uvs.insert(uvs.end(), t, t + 2);
  }

  void face(LineCursor& c, const SourceLocation& where) {
    const std::size_t first = out.corner_vertex.size();
    bool any_uv = false, any_missing_uv = false;
    while (!c.at_end()) {
      long v = 0, t = 0;
      if (!c.corner(v, t)) throw ConfigError(where, "face corner is not of the form v, v/vt, v//vn or v/vt/vn");
      out.corner_vertex.push_back(resolve_index(v, positions.size() / 3, "vertex", "vertices", where));
      if (t != 0) {
        out.corner_uv.push_back(resolve_index(t, uvs.size() / 2, "texture coordinate", "texture coordinates", where));
        any_uv = true;
      } else {
        any_missing_uv = true;
      }
    }
    const std::size_t corners = out.corner_vertex.size() - first;
    if (corners < 3) throw ConfigError(where, "face has " + std::to_string(corners) + " corners, needs at least 3");
    if (any_uv && any_missing_uv) throw ConfigError(where, "face gives texture coordinates for some corners only");
    if (out.num_faces() == 0) {
      first_face_line = where.line;
      faces_have_uv = any_uv;
    } else if (any_uv != faces_have_uv) {
      throw ConfigError(where, std::string("face ") + (any_uv ? "has" : "has no") +
                                   " texture coordinates but the first face (line " +
                                   std::to_string(first_face_line) + ") " + (any_uv ? "has none" : "has them"));
    }
    out.face_start.push_back(static_cast<int>(out.corner_vertex.size()));
    groups.label_face();
    materials.label_face();
  }

  void parse(const std::string& text) {
    const char* p = text.data();
    const char* const end = p + text.size();
    // A UTF-8 byte-order mark (an editor's save): the first statement's
    // keyword read "\xEF\xBB\xBFv", unknown, and the first vertex was
    // dropped without a word (then "face refers to vertex 6904 but 6903 ...").
    if (text.size() >= 3 && std::memcmp(p, "\xEF\xBB\xBF", 3) == 0) p += 3;
    SourceLocation where{path, 0};
    while (p < end) {
      ++where.line;
      const char* eol = static_cast<const char*>(std::memchr(p, '\n', static_cast<std::size_t>(end - p)));
      if (!eol) eol = end;
      const char* hash = static_cast<const char*>(std::memchr(p, '#', static_cast<std::size_t>(eol - p)));
      LineCursor c(p, hash ? hash : eol);
      p = eol + 1;
      const std::string_view key = c.word();
      if (key == "v") {
        vertex(c, where);
      } else if (key == "vt") {
        texcoord(c, where);
      } else if (key == "f") {
        face(c, where);
      } else if (key == "g" || key == "o") {
        groups.set(c.rest());
      } else if (key == "usemtl") {
        materials.set(c.rest());
      }
      // vn, s, mtllib, l, p and unknown statements carry nothing we keep.
    }
    finish();
  }

  void finish() {
    using RowMajor3 = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
    using RowMajor2 = Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>;
    out.vertices = Eigen::Map<const RowMajor3>(positions.data(), static_cast<Eigen::Index>(positions.size() / 3), 3);
    if (faces_have_uv) {
      out.uv = Eigen::Map<const RowMajor2>(uvs.data(), static_cast<Eigen::Index>(uvs.size() / 2), 2);
    } else {
      out.corner_uv.clear();
    }
  }
};

}  // namespace

PolygonMesh read_obj_polygons(const std::filesystem::path& file) {
  ObjParser parser;
  parser.path = file.string();
  parser.parse(mesh_io::read_file_bytes(file));
  if (parser.out.num_vertices() == 0) throw ConfigError(SourceLocation{parser.path, 0}, "no vertices ('v' lines) in this OBJ file");
  return std::move(parser.out);
}

}  // namespace drape
