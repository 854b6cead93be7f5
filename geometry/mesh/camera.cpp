#include "geometry/mesh/camera.h"

#include <cmath>
#include <numeric>
#include <sstream>

#include "geometry/core/input_error.h"

namespace skyband {
namespace {

std::string vec_text(const Vec3& v) {
  std::ostringstream s;
  s << '[' << v.x() << ", " << v.y() << ", " << v.z() << ']';
  return s.str();
}

bool finite(const Vec3& v) {
  return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z());
}

}  // namespace

std::vector<Vec2> pixel_sample_offsets(int samples) {
  if (samples < 1 || samples > 4096) throw InputError("samples per pixel " + std::to_string(samples) + ": must be in [1, 4096]");
  int a = 1;
  if (samples > 2) {
    const double target = samples * (std::sqrt(5.0) - 1.0) / 2.0;
    const int base = static_cast<int>(std::lround(target));
    // Nearest integer to the golden fraction that is coprime with S (search outward; 1 always is).
    for (int d = 0; d < samples; ++d) {
      if (base - d >= 1 && std::gcd(base - d, samples) == 1) {
        a = base - d;
        break;
      }
      if (base + d < samples && std::gcd(base + d, samples) == 1) {
        a = base + d;
        break;
      }
    }
  }
  std::vector<Vec2> o(static_cast<std::size_t>(samples));
  for (int i = 0; i < samples; ++i) {
    const double x = (i + 0.5) / samples;
    const double y = std::fmod((i + 0.5) * a, static_cast<double>(samples)) / samples;
    o[static_cast<std::size_t>(i)] = Vec2(x, y);
  }
  return o;
}

PinholeCamera::PinholeCamera(const CameraSpec& spec) : spec_(spec) {
  if (!finite(spec.position)) throw InputError("camera.position " + vec_text(spec.position) + ": not finite");
  if (!finite(spec.look_at)) throw InputError("camera.look_at " + vec_text(spec.look_at) + ": not finite");
  if (!finite(spec.up)) throw InputError("camera.up " + vec_text(spec.up) + ": not finite");
  const Vec3 d = spec.look_at - spec.position;
  if (!(d.norm() > 0)) throw InputError("camera.look_at " + vec_text(spec.look_at) + ": equals camera.position");
  forward_ = d.normalized();
  if (!(spec.up.norm() > 0)) throw InputError("camera.up " + vec_text(spec.up) + ": zero vector");
  const Vec3 r = forward_.cross(spec.up.normalized());
  if (!(r.norm() > 1e-9)) throw InputError("camera.up " + vec_text(spec.up) + ": parallel to the view direction");
  right_ = r.normalized();
  up_ = right_.cross(forward_);
  if (!(spec.vertical_fov_deg > 0 && spec.vertical_fov_deg < 180))
    throw InputError("camera.fov_deg " + std::to_string(spec.vertical_fov_deg) + ": must be in (0, 180) degrees");
  if (spec.width < 1 || spec.width > 16384)
    throw InputError("image.width " + std::to_string(spec.width) + ": must be in [1, 16384] pixels");
  if (spec.height < 1 || spec.height > 16384)
    throw InputError("image.height " + std::to_string(spec.height) + ": must be in [1, 16384] pixels");
  half_height_ = std::tan(0.5 * spec.vertical_fov_deg * kPi / 180.0);
}

Ray PinholeCamera::primary_ray(double image_x, double image_y) const {
  // Image plane at unit distance: y spans [−half_height, +half_height] over the image height.
  const double scale = 2.0 * half_height_ / spec_.height;
  const double px = (image_x - 0.5 * spec_.width) * scale;
  const double py = (0.5 * spec_.height - image_y) * scale;
  Ray ray;
  ray.origin = spec_.position;
  ray.direction = (forward_ + px * right_ + py * up_).normalized();
  ray.t_min = 0;
  return ray;
}

}  // namespace skyband
