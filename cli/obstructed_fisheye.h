#pragma once
// The fisheye of what one point of a model sees (`skyband sky --at X,Y,Z --mesh ...`): the
// same equi-angular projection as the open-sky fisheye (zenith at the centre, horizon on the
// inscribed circle, north up, east left: the sky seen from below), each pixel's direction
// decided exactly against the point's visible sky (SkyVisibility::direction_visible: a look-up,
// the exact sample-plane test near a boundary). The HDR layers: "sky" (the sky's radiance where
// visible, 0 where hidden) and "visible" (1 or 0). The picture: the tone-mapped sky where
// visible, grey where hidden (by the scene, or behind the point's face), the exact horizon in
// red (the highest occluded elevation per azimuth, normal up: geometry/horizon/horizon_profile.h) and
// N, E, S, W at the rim; optionally the sun's path over a day (dots every step, larger at the
// full hours), yellow where the point sees the sun, dark orange where the scene or its own face
// hides it (each decided like a pixel).
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "geometry/bands/band_visibility.h"
#include "geometry/mesh/scene.h"

namespace skyband::cli {

// One sun position of a day's path: unit world direction; `hour` marks a full hour.
struct SunPathMark {
  Vec3 direction;
  bool hour = false;
};

struct ObstructedFisheye {
  int size = 0;
  std::vector<float> sky_rgb;         // size² × 3, linear
  std::vector<float> visible_rgb;     // size² × 3, 1 where visible
  std::vector<std::uint8_t> picture;  // size² × 3, 8-bit sRGB with the drawings
  double svf = 0, sky_exposure = 0;
  std::size_t visible_pixels = 0, sky_pixels = 0;    // inside the circle
  std::size_t sun_marks_up = 0, sun_marks_seen = 0;  // path marks above the horizon / seen by the point
};

// `radiance_rgb(d)`: linear RGB of the sky in unit direction d (above the horizon).
// `exposure` ≤ 0: automatic (png_writer.h).
ObstructedFisheye render_obstructed_fisheye(const Scene& scene, const QueryPoint& q, int size,
                                            const std::function<Vec3(const Vec3&)>& radiance_rgb, double exposure,
                                            std::span<const SunPathMark> sun_path = {});

// The unit direction of pixel (col, row) of a size × size fisheye, or false outside the circle.
bool fisheye_direction(int size, int col, int row, Vec3& d);

}  // namespace skyband::cli
