// Validating OFF reader (Geomview "OFF" format, http://www.geomview.org/docs/html/OFF.html):
// header keyword [ST][C][N][4][n]OFF, counts "vertices faces [edges]", one vertex per line
// (x y z, then optional normal / colour / texture values, ignored), one face per line
// ("n i0 … i(n−1)" then optional colour, ignored). `#` starts a comment anywhere.
// The declared counts are never trusted for memory: the vertices reserved are at most what the
// bytes after the counts can hold (a vertex line is at least "0 0 0" and a line end, 6 bytes; the
// last line may lack its line end), and vertices and faces are read line by line as the data
// comes, so a lying count ends in an error at the end of the data.
#include <algorithm>

#include "geometry/core/input_error.h"
#include "io/mesh_reader.h"
#include "io/utf8_text.h"

namespace skyband::mesh_io {

PolygonSoup parse_off(const std::string& name, const std::string& bytes) {
  PolygonSoup soup;
  soup.format = "OFF";
  soup.not_for_openmesh = "OFF is read by skyband's own reader only";  // why: mesh_reader.h, step 2
  soup.polygon_start.push_back(0);
  enum class Stage { kHeader, kCounts, kVertices, kFaces, kTrailing } stage = Stage::kHeader;
  long long vertex_count = -1, face_count = -1;
  std::size_t trailing_lines = 0, last_line = 0;
  std::vector<std::string_view> tokens;
  std::vector<long long> counts;
  auto where = [&](std::size_t line) { return name + ":" + std::to_string(line) + ": "; };
  reject_nul_bytes(name, bytes, "the OFF text");

  for_each_line(bytes, [&](std::size_t line, std::string_view text) {
    last_line = line;
    if (const auto hash = text.find('#'); hash != std::string_view::npos) text = text.substr(0, hash);
    split_tokens(text, tokens);
    if (tokens.empty()) return;
    std::size_t first = 0;
    if (stage == Stage::kHeader) {
      std::string_view keyword = tokens[0];
      if (keyword.size() < 3 || keyword.substr(keyword.size() - 3) != "OFF")
        throw InputError(where(line) + "not an OFF file: the header is '" + printable_text(tokens[0]) +
                         "', expected OFF, NOFF, COFF, CNOFF, STOFF or similar");
      const std::string_view prefix = keyword.substr(0, keyword.size() - 3);
      if (prefix.find('4') != std::string_view::npos || prefix.find('n') != std::string_view::npos)
        throw InputError(where(line) + "OFF variant '" + printable_text(keyword) +
                         "' (4D or n-dimensional vertices) is not supported; use 3D OFF");
      if (std::any_of(prefix.begin(), prefix.end(), [](char c) { return c != 'S' && c != 'T' && c != 'C' && c != 'N'; }))
        throw InputError(where(line) + "unknown OFF header '" + printable_text(keyword) + "'");
      if (tokens.size() > 1 && tokens[1] == "BINARY")
        throw InputError(where(line) + "binary OFF is not supported; use ASCII OFF");
      if (prefix != "") soup.format = "OFF (" + std::string(keyword) + " header)";
      stage = Stage::kCounts;
      first = 1;
      if (tokens.size() == 1) return;
    }
    if (stage == Stage::kCounts) {
      for (std::size_t i = first; i < tokens.size() && counts.size() < 3; ++i) {
        const long long c = parse_integer(tokens[i], name, line,
                                          counts.empty()       ? "vertex count"
                                          : counts.size() == 1 ? "face count"
                                                               : "edge count");
        if (c < 0) throw InputError(where(line) + "negative count " + std::to_string(c));
        counts.push_back(c);
      }
      if (counts.size() < 2) return;  // the face count may follow on the next line
      vertex_count = counts[0];
      face_count = counts[1];
      if (vertex_count > 0xFFFFFFFFll || face_count > 0xFFFFFFFFll)
        throw InputError(where(line) + "counts " + std::to_string(vertex_count) + " " + std::to_string(face_count) +
                         " are too large");
      // A lying count must cost an error, not gigabytes: nothing is reserved beyond the vertex
      // lines the bytes after the counts can hold (see the top of this file). The loop over the
      // lines is driven by the data, so a count larger than the file ends in "file ends after k
      // of N vertices/faces", naming where the data stopped.
      const std::size_t counts_end = static_cast<std::size_t>(text.data() - bytes.data()) + text.size();
      const std::size_t room = (bytes.size() - counts_end + 1) / 6;
      soup.faces_declared = static_cast<std::size_t>(face_count);
      soup.vertices.reserve(std::min(static_cast<std::size_t>(vertex_count), room));
      stage = vertex_count > 0 ? Stage::kVertices : face_count > 0 ? Stage::kFaces : Stage::kTrailing;
      return;
    }
    if (stage == Stage::kVertices) {
      if (tokens.size() < 3)
        throw InputError(where(line) + "vertex " + std::to_string(soup.vertices.size()) + " has " +
                         std::to_string(tokens.size()) + " values, 3 coordinates needed: '" + printable_text(text) + "'");
      static const char* axes[3] = {"x coordinate", "y coordinate", "z coordinate"};
      Vec3 p;
      for (int i = 0; i < 3; ++i) p[i] = parse_coordinate(tokens[static_cast<std::size_t>(i)], name, line, axes[i]);
      add_vertex(soup, p);
      if (static_cast<long long>(soup.vertices.size()) == vertex_count) stage = face_count > 0 ? Stage::kFaces : Stage::kTrailing;
      return;
    }
    if (stage == Stage::kFaces) {
      const std::size_t face = soup.polygon_count();
      const long long n = parse_integer(tokens[0], name, line, "face vertex count");
      if (n < 3)
        throw InputError(where(line) + "face " + std::to_string(face) + " declares " + std::to_string(n) +
                         " vertices, at least 3 needed");
      if (static_cast<long long>(tokens.size()) - 1 < n)
        throw InputError(where(line) + "face " + std::to_string(face) + " declares " + std::to_string(n) + " vertices, has " +
                         std::to_string(tokens.size() - 1));
      for (long long k = 0; k < n; ++k) {
        const long long index = parse_integer(tokens[static_cast<std::size_t>(k) + 1], name, line, "face vertex index");
        if (index < 0 || index >= vertex_count)
          throw InputError(where(line) + "face " + std::to_string(face) + " vertex index " + std::to_string(index) +
                           " is out of range [0, " + std::to_string(vertex_count) + ")");
        soup.indices.push_back(static_cast<std::uint32_t>(index));
      }
      soup.polygon_start.push_back(static_cast<std::uint32_t>(soup.indices.size()));
      if (static_cast<long long>(soup.polygon_count()) == face_count) stage = Stage::kTrailing;
      return;
    }
    ++trailing_lines;
  });

  const std::string at_end = name + ":" + std::to_string(last_line) + ": ";
  switch (stage) {
    case Stage::kHeader:
      if (bytes.find_first_not_of(" \t\r\n") == std::string::npos) return soup;  // empty: reported by the caller
      throw InputError(name + ": no OFF header (only comments)");
    case Stage::kCounts:
      throw InputError(at_end + "file ends before the OFF vertex and face counts");
    case Stage::kVertices:
      throw InputError(at_end + "file ends after " + std::to_string(soup.vertices.size()) + " of " +
                       std::to_string(vertex_count) + " vertices");
    case Stage::kFaces:
      throw InputError(at_end + "file ends after " + std::to_string(soup.polygon_count()) + " of " + std::to_string(face_count) +
                       " faces");
    case Stage::kTrailing:
      break;
  }
  if (trailing_lines) soup.notes.push_back("ignored " + std::to_string(trailing_lines) + " line(s) after the last declared face");
  return soup;
}

}  // namespace skyband::mesh_io
