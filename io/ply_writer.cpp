#include "io/ply_writer.h"

#include <bit>
#include <cstdio>
#include <cstring>

#include "geometry/core/input_error.h"
#include "io/atomic_file.h"

namespace skyband {

namespace {

// Little-endian bytes of a trivially copyable value (x86-64 and ARM64 are little-endian; checked
// at compile time).
static_assert(std::endian::native == std::endian::little, "the PLY writer assumes a little-endian host");

template <class T>
void put(std::vector<char>& out, const T& v) {
  const auto* b = reinterpret_cast<const char*>(&v);
  out.insert(out.end(), b, b + sizeof v);
}

}  // namespace

void write_face_values_ply(const std::filesystem::path& file, const FaceValuesPly& ply) {
  const TriangleSoup& soup = *ply.soup;
  const std::size_t nt = soup.triangle_count();
  if (ply.values.size() != nt || ply.rgb.size() != nt)
    throw InputError(file.string() + ": " + std::to_string(ply.values.size()) + " values and " + std::to_string(ply.rgb.size()) +
                     " colours for " + std::to_string(nt) + " faces");
  std::string header = "ply\nformat binary_little_endian 1.0\n";
  for (const std::string& c : ply.comments) {
    if (c.find_first_of("\r\n") != std::string::npos)
      throw InputError(file.string() + ": a PLY comment cannot hold a line break");
    header += "comment " + c + "\n";
  }
  header += "element vertex " + std::to_string(soup.vertices.size()) +
            "\nproperty double x\nproperty double y\nproperty double z\n"
            "element face " +
            std::to_string(nt) +
            "\nproperty list uchar uint vertex_indices\nproperty float value\n"
            "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n";
  std::vector<char> body;
  body.reserve(soup.vertices.size() * 24 + nt * 20);
  for (const Vec3& v : soup.vertices) put(body, v.x()), put(body, v.y()), put(body, v.z());
  for (std::size_t t = 0; t < nt; ++t) {
    put(body, std::uint8_t(3));
    for (const std::uint32_t i : soup.triangles[t]) put(body, i);
    put(body, ply.values[t]);
    for (const std::uint8_t c : ply.rgb[t]) put(body, c);
  }
  write_atomically(file, [&](const std::filesystem::path& temp) {
    std::FILE* f = std::fopen(temp.c_str(), "wb");
    if (!f) throw InputError(file.string() + ": cannot write");
    bool ok = std::fwrite(header.data(), 1, header.size(), f) == header.size();
    ok = std::fwrite(body.data(), 1, body.size(), f) == body.size() && ok;
    ok = std::fclose(f) == 0 && ok;
    if (!ok) throw InputError(file.string() + ": write failed (disk full?)");
  });
}

}  // namespace skyband
