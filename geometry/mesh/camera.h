#pragma once
// Pinhole camera: primary rays per pixel with deterministic anti-aliasing.
//
// Image convention: pixel (column c, row r), row 0 at the TOP; a sample at offset (ox, oy) ∈
// [0, 1)² inside the pixel sits at image coordinates (c + ox, r + oy). The vertical field of view
// spans the image height; the horizontal one follows from the aspect ratio (square pixels).
// World frame: metres, x east, y north, z up.
//
// Anti-aliasing pattern (no random numbers): for S samples a rank-1 lattice
//     o_i = ((i + ½)/S, frac((i + ½)·a/S)),  i = 0..S−1,
// with a the integer nearest S·(√5 − 1)/2 that is coprime with S (a = 1 for S ≤ 2). Every column
// and every row stratum of width 1/S holds exactly one sample (a permutation, because a is coprime
// with S); S = 1 is the pixel centre and S = 4 is the classic rotated grid (RGSS).
#include <vector>

#include "geometry/core/vec3.h"
#include "geometry/mesh/scene.h"

namespace skyband {

struct CameraSpec {
  Vec3 position{0, -10, 2};      // metres
  Vec3 look_at{0, 0, 2};         // metres
  Vec3 up{0, 0, 1};              // need not be unit or orthogonal to the view direction
  double vertical_fov_deg = 45;  // full angle, (0, 180)
  int width = 640;               // pixels
  int height = 480;
};

// Sub-pixel sample offsets of the pattern above, in [0, 1)². Throws InputError if samples < 1.
std::vector<Vec2> pixel_sample_offsets(int samples);

class PinholeCamera {
 public:
  // Validates the spec (finite values, position ≠ look_at, up not parallel to the view direction,
  // 0 < fov < 180, 1 ≤ width, height ≤ 16384); throws InputError naming the field and value.
  explicit PinholeCamera(const CameraSpec& spec);

  const CameraSpec& spec() const { return spec_; }
  int width() const { return spec_.width; }
  int height() const { return spec_.height; }
  const Vec3& forward() const { return forward_; }  // unit view direction

  // Ray through image coordinates (x right, y down, in pixels; (0,0) = top-left corner of the
  // image); direction is unit, origin the eye, t_min = 0.
  Ray primary_ray(double image_x, double image_y) const;

 private:
  CameraSpec spec_;
  Vec3 forward_, right_, up_;  // orthonormal camera frame (right = forward × up)
  double half_height_ = 0;     // tan(fov/2): half the image plane height at unit distance
};

}  // namespace skyband
