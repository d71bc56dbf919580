#include "geometry/surface_formats.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "core/errors.hpp"

namespace hm::geometry {
namespace {

using mesh::Index;

/// Vertices and triangles as a reader finds them; polygons are fanned from their first vertex.
class SurfaceBuilder {
 public:
  explicit SurfaceBuilder(std::string file) : file_(std::move(file)) {}

  void vertex(double x, double y, double z, const std::string& where) {
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
      input_error("geometry file '{}', {}: vertex ({}, {}, {}) is not finite", file_, where, x, y,
                  z);
    vertices_.push_back({x, y, z});
  }
  Index vertex_count() const { return static_cast<Index>(vertices_.size()); }

  /// A face of 0-based vertex indices (checked against the vertices in finish()).
  void polygon(const std::vector<Index>& corners) {
    if (corners.size() < 3) {
      ++skipped_;
      return;
    }
    for (std::size_t k = 1; k + 1 < corners.size(); ++k)
      triangles_.push_back({corners[0], corners[k], corners[k + 1]});
  }

  SurfaceFile finish() const {
    const Index n = vertex_count();
    for (std::size_t t = 0; t < triangles_.size(); ++t)
      for (Index v : triangles_[t])
        if (v < 0 || v >= n)
          input_error(
              "geometry file '{}': a face refers to vertex {} (counting from 1), the file has {} "
              "vertices",
              file_, v + 1, n);
    SurfaceFile out;
    out.skipped = skipped_;
    out.surface.dim = 3;
    out.surface.vertices.resize(n, 3);
    for (Index i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c)
        out.surface.vertices(i, c) = vertices_[static_cast<std::size_t>(i)][c];
    out.surface.cells.resize(static_cast<Index>(triangles_.size()), 3);
    for (std::size_t t = 0; t < triangles_.size(); ++t)
      for (int c = 0; c < 3; ++c) out.surface.cells(static_cast<Index>(t), c) = triangles_[t][c];
    return out;
  }

  const std::string& file() const { return file_; }

 private:
  std::string file_;
  std::vector<std::array<double, 3>> vertices_;
  std::vector<std::array<Index, 3>> triangles_;
  Index skipped_ = 0;
};

std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) input_error("geometry file '{}' cannot be read", path.string());
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// The whitespace-separated words of a line.
std::vector<std::string_view> words_of(std::string_view line) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    const std::size_t start = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
  return words;
}

/// Calls visit(line number, words) for every line of `text`.
template <typename Visit>
void for_each_line(std::string_view text, Visit&& visit) {
  std::size_t start = 0;
  for (int number = 1; start < text.size(); ++number) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    visit(number, words_of(text.substr(start, end - start)));
    start = end + 1;
  }
}

bool parse_double(std::string_view text, double& value) {
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && ptr == text.data() + text.size();
}

bool parse_long(std::string_view text, long long& value) {
  if (!text.empty() && text[0] == '+') text.remove_prefix(1);
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && ptr == text.data() + text.size();
}

// ---- STL ----------------------------------------------------------------------------------------

constexpr std::size_t stl_header = 84, stl_record = 50;

/// A little-endian 32-bit word at p.
std::uint32_t little_endian_u32(const char* p) {
  const auto* b = reinterpret_cast<const unsigned char*>(p);
  return std::uint32_t{b[0]} | std::uint32_t{b[1]} << 8 | std::uint32_t{b[2]} << 16 |
         std::uint32_t{b[3]} << 24;
}

bool is_binary_stl(const std::string& bytes) {
  if (bytes.size() < stl_header) return false;
  const std::uint32_t n = little_endian_u32(bytes.data() + 80);
  return bytes.size() == stl_header + stl_record * static_cast<std::size_t>(n);
}

float little_endian_float(const char* p) {
  return std::bit_cast<float>(little_endian_u32(p));
}

SurfaceFile read_binary_stl(const std::string& bytes, SurfaceBuilder b) {
  const std::size_t n = (bytes.size() - stl_header) / stl_record;
  for (std::size_t t = 0; t < n; ++t) {
    const char* record = bytes.data() + stl_header + t * stl_record;
    std::vector<Index> corners;
    for (int v = 0; v < 3; ++v) {
      const char* p = record + 12 + 12 * v;  // after the facet normal
      b.vertex(little_endian_float(p), little_endian_float(p + 4), little_endian_float(p + 8),
               "triangle " + std::to_string(t + 1));
      corners.push_back(b.vertex_count() - 1);
    }
    b.polygon(corners);
  }
  return b.finish();
}

/// ASCII STL: solid NAME, then facets (facet normal n n n / outer loop / vertex x y z ×3 /
/// endloop / endfacet), endsolid NAME; several solids may follow each other.
SurfaceFile read_ascii_stl(const std::string& text, SurfaceBuilder b) {
  enum class At { file, solid, facet, loop, loop_end } at = At::file;
  std::vector<Index> corners;
  const std::string& file = b.file();
  auto fail = [&](int line, const std::vector<std::string_view>& w, const char* expected) {
    std::string got;
    for (auto word : w) {
      if (!got.empty()) got += ' ';
      got += word;
    }
    input_error("geometry file '{}', line {}: '{}' where an ASCII STL has {}", file, line, got,
                expected);
  };
  for_each_line(text, [&](int line, const std::vector<std::string_view>& w) {
    if (w.empty()) return;
    double x = 0, y = 0, z = 0;
    switch (at) {
      case At::file:
        if (w[0] != "solid") fail(line, w, "'solid NAME'");
        at = At::solid;
        return;
      case At::solid:
        if (w[0] == "endsolid") {
          at = At::file;
          return;
        }
        if (w.size() != 5 || w[0] != "facet" || w[1] != "normal" || !parse_double(w[2], x) ||
            !parse_double(w[3], y) || !parse_double(w[4], z))
          fail(line, w, "'facet normal NX NY NZ' or 'endsolid'");
        at = At::facet;
        return;
      case At::facet:
        if (w.size() != 2 || w[0] != "outer" || w[1] != "loop") fail(line, w, "'outer loop'");
        corners.clear();
        at = At::loop;
        return;
      case At::loop:
        if (w.size() == 1 && w[0] == "endloop") {
          if (corners.size() != 3) fail(line, w, "three vertices before 'endloop'");
          b.polygon(corners);
          at = At::loop_end;
          return;
        }
        if (w.size() != 4 || w[0] != "vertex" || !parse_double(w[1], x) || !parse_double(w[2], y) ||
            !parse_double(w[3], z))
          fail(line, w, "'vertex X Y Z' or 'endloop'");
        b.vertex(x, y, z, "line " + std::to_string(line));
        corners.push_back(b.vertex_count() - 1);
        return;
      case At::loop_end:
        if (w.size() != 1 || w[0] != "endfacet") fail(line, w, "'endfacet'");
        at = At::solid;
        return;
    }
  });
  if (at != At::file && at != At::solid)
    input_error("geometry file '{}': the ASCII STL ends inside a facet", file);
  return b.finish();
}

SurfaceFile read_stl(const std::filesystem::path& path) {
  const std::string bytes = read_bytes(path);
  SurfaceBuilder b(path.string());
  if (is_binary_stl(bytes)) return read_binary_stl(bytes, std::move(b));
  const auto first = bytes.find_first_not_of(" \t\r\n");
  if (first != std::string::npos && bytes.compare(first, 5, "solid") == 0)
    return read_ascii_stl(bytes, std::move(b));
  const std::uint32_t n = bytes.size() >= stl_header ? little_endian_u32(bytes.data() + 80) : 0;
  input_error(
      "geometry file '{}' is neither an ASCII STL (starting with 'solid') nor a binary STL "
      "({} bytes: a binary STL of the {} triangles its header counts has {} bytes)",
      path.string(), bytes.size(), n, stl_header + stl_record * static_cast<std::size_t>(n));
}

// ---- OBJ ----------------------------------------------------------------------------------------

/// Wavefront OBJ: `v X Y Z [W]` vertices, `f A B C ...` faces (A as i, i/t, i//n or i/t/n; a
/// negative i counts back from the last vertex read); `l` and `p` (lines, points) are skipped;
/// every other statement (vt, vn, o, g, s, usemtl, ...) carries nothing a wall needs.
SurfaceFile read_obj(const std::filesystem::path& path) {
  const std::string text = read_bytes(path);
  SurfaceBuilder b(path.string());
  Index skipped_lines = 0;
  for_each_line(text, [&](int line, std::vector<std::string_view> w) {
    for (std::size_t k = 0; k < w.size(); ++k)
      if (w[k].front() == '#') {
        w.resize(k);
        break;
      }
    if (w.empty()) return;
    const std::string where = "line " + std::to_string(line);
    if (w[0] == "v") {
      double x = 0, y = 0, z = 0;
      if (w.size() < 4 || !parse_double(w[1], x) || !parse_double(w[2], y) ||
          !parse_double(w[3], z))
        input_error("geometry file '{}', {}: expected 'v X Y Z', got {} words", path.string(),
                    where, w.size());
      b.vertex(x, y, z, where);
    } else if (w[0] == "f") {
      std::vector<Index> corners;
      for (std::size_t k = 1; k < w.size(); ++k) {
        long long i = 0;
        const std::string_view index = w[k].substr(0, w[k].find('/'));
        if (!parse_long(index, i) || i == 0)
          input_error(
              "geometry file '{}', {}: face corner '{}' is not a vertex number (1, 2, … or -1, "
              "-2, … from the last vertex)",
              path.string(), where, w[k]);
        const long long zero_based = i > 0 ? i - 1 : b.vertex_count() + i;
        if (zero_based < 0 || zero_based > std::numeric_limits<Index>::max())
          input_error("geometry file '{}', {}: face corner '{}' refers to no vertex", path.string(),
                      where, w[k]);
        corners.push_back(static_cast<Index>(zero_based));
      }
      b.polygon(corners);
    } else if (w[0] == "l" || w[0] == "p") {
      ++skipped_lines;
    }
  });
  SurfaceFile out = b.finish();
  out.skipped += skipped_lines;
  return out;
}

// ---- PLY ----------------------------------------------------------------------------------------

enum class PlyType { i8, u8, i16, u16, i32, u32, f32, f64 };

std::optional<PlyType> ply_type(std::string_view t) {
  static const std::array<std::pair<std::string_view, PlyType>, 16> names{
      {{"char", PlyType::i8},
       {"int8", PlyType::i8},
       {"uchar", PlyType::u8},
       {"uint8", PlyType::u8},
       {"short", PlyType::i16},
       {"int16", PlyType::i16},
       {"ushort", PlyType::u16},
       {"uint16", PlyType::u16},
       {"int", PlyType::i32},
       {"int32", PlyType::i32},
       {"uint", PlyType::u32},
       {"uint32", PlyType::u32},
       {"float", PlyType::f32},
       {"float32", PlyType::f32},
       {"double", PlyType::f64},
       {"float64", PlyType::f64}}};
  for (const auto& [name, type] : names)
    if (t == name) return type;
  return std::nullopt;
}

std::size_t ply_size(PlyType t) {
  switch (t) {
    case PlyType::i8:
    case PlyType::u8:
      return 1;
    case PlyType::i16:
    case PlyType::u16:
      return 2;
    case PlyType::i32:
    case PlyType::u32:
    case PlyType::f32:
      return 4;
    case PlyType::f64:
      return 8;
  }
  return 8;
}

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::f32;
  bool list = false;
  PlyType count_type = PlyType::u8;
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

enum class PlyFormat { ascii, little, big };

struct PlyHeader {
  PlyFormat format = PlyFormat::ascii;
  std::vector<PlyElement> elements;
  std::size_t body = 0;  ///< byte offset of the data
  int body_line = 0;     ///< line number of the data's first line (ASCII)
};

PlyHeader read_ply_header(const std::string& bytes, const std::string& file) {
  PlyHeader h;
  std::size_t start = 0;
  for (int number = 1;; ++number) {
    const std::size_t end = bytes.find('\n', start);
    if (end == std::string::npos)
      input_error("geometry file '{}': its PLY header has no end_header line", file);
    const std::string_view line(bytes.data() + start, end - start);
    const auto w = words_of(line);
    start = end + 1;
    auto bad = [&](const char* expected) {
      input_error("geometry file '{}', line {}: '{}' is not a PLY header line (expected {})", file,
                  number, std::string(line.substr(0, 200)), expected);
    };
    if (number == 1) {
      if (w.size() != 1 || w[0] != "ply") bad("'ply'");
      continue;
    }
    if (number == 2) {
      if (w.size() != 3 || w[0] != "format")
        bad("format ascii|binary_little_endian|binary_big_endian 1.0");
      if (w[1] == "ascii")
        h.format = PlyFormat::ascii;
      else if (w[1] == "binary_little_endian")
        h.format = PlyFormat::little;
      else if (w[1] == "binary_big_endian")
        h.format = PlyFormat::big;
      else
        bad("format ascii|binary_little_endian|binary_big_endian 1.0");
      continue;
    }
    if (w.empty()) continue;
    if (w[0] == "comment" || w[0] == "obj_info") continue;
    if (w.size() == 1 && w[0] == "end_header") {
      h.body = start;
      h.body_line = number + 1;
      return h;
    }
    if (w[0] == "element") {
      unsigned long long count = 0;
      if (w.size() != 3 ||
          std::from_chars(w[2].data(), w[2].data() + w[2].size(), count).ec != std::errc())
        bad("element NAME COUNT");
      h.elements.push_back({std::string(w[1]), count, {}});
      continue;
    }
    if (w[0] == "property" && !h.elements.empty()) {
      PlyProperty p;
      if (w.size() == 3 && ply_type(w[1])) {
        p = {std::string(w[2]), *ply_type(w[1]), false, PlyType::u8};
      } else if (w.size() == 5 && w[1] == "list" && ply_type(w[2]) && ply_type(w[3])) {
        p = {std::string(w[4]), *ply_type(w[3]), true, *ply_type(w[2])};
      } else {
        bad("property TYPE NAME or property list TYPE TYPE NAME");
      }
      h.elements.back().properties.push_back(p);
      continue;
    }
    bad("element NAME COUNT, property TYPE NAME, property list TYPE TYPE NAME, comment or "
        "end_header");
  }
}

/// The values of a PLY body in order, whatever its format.
class PlyValues {
 public:
  PlyValues(const std::string& bytes, const PlyHeader& h, std::string file)
      : bytes_(bytes), format_(h.format), at_(h.body), line_(h.body_line), file_(std::move(file)) {}

  double next(PlyType type) {
    return format_ == PlyFormat::ascii ? next_word() : next_binary(type);
  }

 private:
  double next_word() {
    while (at_ < bytes_.size() && std::isspace(static_cast<unsigned char>(bytes_[at_])))
      line_ += bytes_[at_++] == '\n';
    const std::size_t start = at_;
    while (at_ < bytes_.size() && !std::isspace(static_cast<unsigned char>(bytes_[at_]))) ++at_;
    if (start == at_) input_error("geometry file '{}': the PLY data ends early", file_);
    double v = 0;
    const std::string_view word(bytes_.data() + start, at_ - start);
    if (!parse_double(word, v))
      input_error("geometry file '{}', line {}: '{}' is not a number", file_, line_,
                  std::string(word.substr(0, 40)));
    return v;
  }

  double next_binary(PlyType type) {
    const std::size_t n = ply_size(type);
    if (bytes_.size() - at_ < n)
      input_error("geometry file '{}': the binary PLY data ends early (byte {})", file_, at_);
    unsigned char b[8];
    std::memcpy(b, bytes_.data() + at_, n);
    const bool swap = (format_ == PlyFormat::big) != (std::endian::native == std::endian::big);
    if (swap) std::reverse(b, b + n);
    at_ += n;
    auto as = [&](auto value) {
      std::memcpy(&value, b, sizeof value);
      return static_cast<double>(value);
    };
    switch (type) {
      case PlyType::i8:
        return as(std::int8_t{});
      case PlyType::u8:
        return as(std::uint8_t{});
      case PlyType::i16:
        return as(std::int16_t{});
      case PlyType::u16:
        return as(std::uint16_t{});
      case PlyType::i32:
        return as(std::int32_t{});
      case PlyType::u32:
        return as(std::uint32_t{});
      case PlyType::f32:
        return as(float{});
      case PlyType::f64:
        return as(double{});
    }
    return 0.0;
  }

  const std::string& bytes_;
  PlyFormat format_;
  std::size_t at_;
  int line_;
  std::string file_;
};

/// A list length or a vertex index: a whole number in [0, limit].
Index whole_number(double v, double limit, const std::string& file, const char* what) {
  if (!(v >= 0.0 && v <= limit && v == std::floor(v)))
    input_error("geometry file '{}': {} {} is not a whole number in [0, {}]", file, what, v, limit);
  return static_cast<Index>(v);
}

/// PLY: the element "vertex" (properties x, y, z) and the element "face" (a list property
/// vertex_indices or vertex_index); other elements and properties are read past.
SurfaceFile read_ply(const std::filesystem::path& path) {
  const std::string bytes = read_bytes(path), file = path.string();
  const PlyHeader h = read_ply_header(bytes, file);
  SurfaceBuilder b(file);
  PlyValues values(bytes, h, file);
  constexpr double max_list = 1e6, max_index = 2e9;
  bool has_vertices = false;
  for (const PlyElement& e : h.elements) {
    if (e.properties.empty()) continue;  // nothing to read, however many
    const bool vertex = e.name == "vertex", face = e.name == "face";
    std::array<int, 3> xyz{-1, -1, -1};
    int corners = -1;
    for (std::size_t k = 0; k < e.properties.size(); ++k) {
      const auto& p = e.properties[k];
      for (int c = 0; c < 3; ++c)
        if (vertex && !p.list && p.name == std::string(1, static_cast<char>('x' + c)))
          xyz[c] = static_cast<int>(k);
      if (face && p.list && (p.name == "vertex_indices" || p.name == "vertex_index"))
        corners = static_cast<int>(k);
    }
    if (vertex && std::count(xyz.begin(), xyz.end(), -1) > 0)
      input_error("geometry file '{}': the PLY element vertex has no x, y and z properties", file);
    has_vertices = has_vertices || vertex;
    for (std::uint64_t item = 0; item < e.count; ++item) {
      std::array<double, 3> x{};
      std::vector<Index> polygon;
      for (std::size_t k = 0; k < e.properties.size(); ++k) {
        const auto& p = e.properties[k];
        if (!p.list) {
          const double v = values.next(p.type);
          for (int c = 0; c < 3; ++c)
            if (xyz[c] == static_cast<int>(k)) x[c] = v;
          continue;
        }
        const Index n = whole_number(values.next(p.count_type), max_list, file, "a list length");
        for (Index j = 0; j < n; ++j) {
          const double v = values.next(p.type);
          if (corners == static_cast<int>(k))
            polygon.push_back(whole_number(v, max_index, file, "a vertex index"));
        }
      }
      if (vertex) b.vertex(x[0], x[1], x[2], "vertex " + std::to_string(item + 1));
      if (corners >= 0) b.polygon(polygon);
    }
  }
  if (!has_vertices) input_error("geometry file '{}': the PLY file has no element vertex", file);
  return b.finish();
}

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace

std::optional<SurfaceFile> read_known_surface_format(const std::filesystem::path& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".stl") return read_stl(path);
  if (ext == ".obj") return read_obj(path);
  if (ext == ".ply") return read_ply(path);
  return std::nullopt;
}

}  // namespace hm::geometry
