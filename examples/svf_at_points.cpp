// The skyband library in a few lines: read a mesh, compute the exact sky view factor and sky
// exposure at calculation points, print them.
//
//   svf_at_points MESH X,Y,Z[,NX,NY,NZ] [X,Y,Z[,NX,NY,NZ] ...]
//
// MESH is any file skyband reads (OBJ, OFF, PLY, STL, CityJSON, CityGML); each point is given in
// the mesh's metres, with an optional unit normal (default: facing up). Built against the installed
// package (examples/CMakeLists.txt: find_package(skyband), target skyband::skyband).
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "skyband/skyband.h"

namespace {

// "x,y,z" or "x,y,z,nx,ny,nz" → a point; InputError naming the argument otherwise.
skyband::QueryPoint parse_point(const std::string& text) {
  std::vector<double> v;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string field = text.substr(start, comma - start);
    std::size_t used = 0;
    double x = 0;
    try {
      x = std::stod(field, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (field.empty() || used != field.size() || !std::isfinite(x))
      throw skyband::InputError("point '" + text + "': '" + field + "' is not a finite number");
    v.push_back(x);
    start = comma + 1;
  }
  if (v.size() != 3 && v.size() != 6)
    throw skyband::InputError("point '" + text + "': expected x,y,z or x,y,z,nx,ny,nz (metres)");
  skyband::QueryPoint q{skyband::Vec3(v[0], v[1], v[2]), skyband::Vec3(0, 0, 1)};
  if (v.size() == 6) {
    const double length = std::sqrt(v[3] * v[3] + v[4] * v[4] + v[5] * v[5]);
    if (!(length > 0)) throw skyband::InputError("point '" + text + "': the normal is zero");
    q.normal = skyband::Vec3(v[3] / length, v[4] / length, v[5] / length);
  }
  return q;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s MESH X,Y,Z[,NX,NY,NZ] ...\n", argv[0]);
    return 2;
  }
  try {
    std::vector<skyband::QueryPoint> points;
    for (int i = 2; i < argc; ++i) points.push_back(parse_point(argv[i]));

    // The mesh as a triangle soup (no topology assumed), then the scene: the soup and its BVH.
    const skyband::Scene scene(skyband::read_mesh(argv[1]));

    // Exact at every point: the exact horizon where the scene seen from the point is closed
    // extruded buildings, the exact union of the occluders' projections elsewhere.
    const skyband::SkyFactorsRun run =
        skyband::compute_sky_factors(scene, points, skyband::VisibilityOptions{}, skyband::SkyFactorsMethod::automatic);

    std::printf("x,y,z,svf,sky_exposure\n");
    for (std::size_t i = 0; i < points.size(); ++i) {
      const skyband::Vec3& p = points[i].position;
      std::printf("%.3f,%.3f,%.3f,%.9f,%.9f\n", p.x(), p.y(), p.z(), run.factors[i].svf, run.factors[i].sky_exposure);
    }
    return 0;
  } catch (const skyband::InputError& e) {
    std::fprintf(stderr, "svf_at_points: %s\n", e.what());
    return 2;
  }
}
