// Validating STL reader (3D Systems "StereoLithography Interface Specification", 1989): binary
// (80-byte header, uint32 little-endian count, 50 bytes per facet: normal, 3 vertices as
// float32, uint16 attribute) and ascii ("solid … facet normal … outer loop vertex x y z …
// endloop endfacet … endsolid"). A file is binary when its size is exactly 84 + 50·count
// (binary files may also start with "solid"), else ascii if it starts with "solid".
// STL stores every facet's corners separately; exactly equal positions are welded here so that
// the mesh has connectivity (the report says so). Facet normals are ignored.
#include <cmath>
#include <cstring>
#include <unordered_map>

#include "geometry/core/input_error.h"
#include "io/mesh_reader.h"
#include "io/utf8_text.h"

namespace skyband::mesh_io {
namespace {

struct Welder {
  struct Key {
    std::uint64_t b[3];
    bool operator==(const Key& o) const { return b[0] == o.b[0] && b[1] == o.b[1] && b[2] == o.b[2]; }
  };
  struct Hash {
    std::size_t operator()(const Key& k) const {
      std::uint64_t h = 1469598103934665603ull;
      for (const std::uint64_t x : k.b) h = (h ^ x) * 1099511628211ull ^ (x >> 31);
      return static_cast<std::size_t>(h);
    }
  };
  std::unordered_map<Key, std::uint32_t, Hash> ids;

  std::uint32_t index_of(PolygonSoup& soup, const Vec3& p) {
    Key k{};
    for (int i = 0; i < 3; ++i) {
      const double v = p[i] + 0.0;  // +0 and −0 are equal positions
      std::memcpy(&k.b[i], &v, sizeof v);
    }
    auto [it, inserted] = ids.emplace(k, static_cast<std::uint32_t>(soup.vertices.size()));
    if (inserted) add_vertex(soup, p);
    return it->second;
  }
};

std::uint32_t read_u32_le(const unsigned char* p) {
  return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 | static_cast<std::uint32_t>(p[2]) << 16 |
         static_cast<std::uint32_t>(p[3]) << 24;
}

float read_f32_le(const unsigned char* p) {
  const std::uint32_t bits = read_u32_le(p);
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

PolygonSoup parse_binary(const std::string& name, const std::string& bytes) {
  PolygonSoup soup;
  soup.format = "STL (binary)";
  soup.polygon_start.push_back(0);
  soup.welded = true;
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  const std::uint32_t count = read_u32_le(data + 80);
  soup.faces_declared = count;
  Welder welder;
  for (std::uint32_t f = 0; f < count; ++f) {
    const unsigned char* facet = data + 84 + 50 * static_cast<std::size_t>(f);
    for (int c = 0; c < 3; ++c) {
      Vec3 p;
      for (int i = 0; i < 3; ++i) {
        const float v = read_f32_le(facet + 12 + 12 * c + 4 * i);
        if (!std::isfinite(v))
          throw InputError(name + ": facet " + std::to_string(f) + " vertex " + std::to_string(c) + " (byte " +
                           std::to_string(84 + 50 * static_cast<std::size_t>(f) + 12 + 12 * c + 4 * i) +
                           "): non-finite coordinate " + std::to_string(v));
        p[i] = static_cast<double>(v);
      }
      soup.indices.push_back(welder.index_of(soup, p));
    }
    soup.polygon_start.push_back(static_cast<std::uint32_t>(soup.indices.size()));
  }
  return soup;
}

PolygonSoup parse_ascii(const std::string& name, const std::string& bytes) {
  PolygonSoup soup;
  soup.format = "STL (ascii)";
  soup.polygon_start.push_back(0);
  soup.welded = true;
  Welder welder;
  enum class Stage { kSolid, kFacetOrEnd, kOuterLoop, kVertexOrEndloop, kEndfacet, kDone } stage = Stage::kSolid;
  std::size_t last_line = 0, corners = 0;
  std::vector<std::string_view> tokens;
  auto where = [&](std::size_t line) { return name + ":" + std::to_string(line) + ": "; };
  auto expect = [&](std::size_t line, const char* what) {
    throw InputError(where(line) + "expected " + what + ", found '" + printable_text(tokens[0]) + "'");
  };
  for_each_line(bytes, [&](std::size_t line, std::string_view text) {
    last_line = line;
    split_tokens(text, tokens);
    if (tokens.empty()) return;
    switch (stage) {
      case Stage::kSolid:
        if (tokens[0] != "solid") expect(line, "'solid'");
        stage = Stage::kFacetOrEnd;
        return;
      case Stage::kFacetOrEnd:
        if (tokens[0] == "endsolid") {
          stage = Stage::kDone;
          return;
        }
        if (tokens[0] != "facet") expect(line, "'facet' or 'endsolid'");
        stage = Stage::kOuterLoop;
        return;
      case Stage::kOuterLoop:
        if (tokens[0] != "outer" || tokens.size() < 2 || tokens[1] != "loop") expect(line, "'outer loop'");
        stage = Stage::kVertexOrEndloop;
        corners = 0;
        return;
      case Stage::kVertexOrEndloop:
        if (tokens[0] == "endloop") {
          if (corners < 3)
            throw InputError(where(line) + "facet " + std::to_string(soup.polygon_count()) + " has " + std::to_string(corners) +
                             " vertices, at least 3 needed");
          soup.polygon_start.push_back(static_cast<std::uint32_t>(soup.indices.size()));
          stage = Stage::kEndfacet;
          return;
        }
        if (tokens[0] != "vertex") expect(line, "'vertex' or 'endloop'");
        if (tokens.size() < 4)
          throw InputError(where(line) + "vertex has " + std::to_string(tokens.size() - 1) + " coordinates, 3 needed");
        {
          static const char* axes[3] = {"x coordinate", "y coordinate", "z coordinate"};
          Vec3 p;
          for (int i = 0; i < 3; ++i) p[i] = parse_coordinate(tokens[static_cast<std::size_t>(i) + 1], name, line, axes[i]);
          soup.indices.push_back(welder.index_of(soup, p));
          ++corners;
        }
        return;
      case Stage::kEndfacet:
        if (tokens[0] != "endfacet") expect(line, "'endfacet'");
        stage = Stage::kFacetOrEnd;
        return;
      case Stage::kDone:
        // Several solids may follow one another in one file.
        if (tokens[0] == "solid") {
          stage = Stage::kFacetOrEnd;
          return;
        }
        expect(line, "'solid' or the end of the file");
    }
  });
  if (stage != Stage::kDone && stage != Stage::kSolid)
    throw InputError(name + ":" + std::to_string(last_line) + ": file ends inside a solid (after " +
                     std::to_string(soup.polygon_count()) + " complete facets)");
  soup.faces_declared = soup.polygon_count();
  return soup;
}

}  // namespace

PolygonSoup parse_stl(const std::string& name, const std::string& bytes) {
  if (bytes.size() >= 84) {
    const std::uint32_t count = read_u32_le(reinterpret_cast<const unsigned char*>(bytes.data()) + 80);
    if (bytes.size() == 84 + 50 * static_cast<std::uint64_t>(count)) {
      PolygonSoup soup = parse_binary(name, bytes);
      soup.notes.push_back("STL: " + std::to_string(3 * soup.polygon_count()) + " facet corners welded into " +
                           std::to_string(soup.vertices.size()) + " vertices (exactly equal positions merged)");
      return soup;
    }
  }
  const std::size_t first = bytes.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) {
    PolygonSoup empty;
    empty.format = "STL";
    empty.polygon_start.push_back(0);
    return empty;  // empty mesh: reported by the caller
  }
  if (bytes.compare(first, 5, "solid") != 0) {
    if (bytes.size() >= 84)
      throw InputError(name + ": neither ascii STL (no 'solid' at the start) nor binary STL (size " +
                       std::to_string(bytes.size()) + " bytes, but the header declares " +
                       std::to_string(read_u32_le(reinterpret_cast<const unsigned char*>(bytes.data()) + 80)) + " facets = " +
                       std::to_string(84 + 50 * static_cast<std::uint64_t>(
                                                    read_u32_le(reinterpret_cast<const unsigned char*>(bytes.data()) + 80))) +
                       " bytes)");
    throw InputError(name + ": not an STL file (" + std::to_string(bytes.size()) + " bytes, no 'solid' at the start)");
  }
  reject_nul_bytes(name, bytes, "the ascii STL text");
  PolygonSoup soup = parse_ascii(name, bytes);
  soup.notes.push_back("STL: " + std::to_string(soup.indices.size()) + " facet corners welded into " +
                       std::to_string(soup.vertices.size()) + " vertices (exactly equal positions merged)");
  return soup;
}

}  // namespace skyband::mesh_io
