#pragma once
// Image-space reuse of the specular sky term (renderer phase 2).
//
// The reflected sky of a glossy surface is the visible sky convolved with a lobe several degrees
// wide, so across a few pixels of one plane it changes smoothly; the ε-march is by far the
// dearest term (specular_sky.h). The image is cut into blocks of B × B pixels (B a power of two
// times 4) refined as a quadtree down to 4 × 4. Per pixel-sample index, the samples at block
// corners are marched exactly, and so are each block's centre and edge midpoints (the corners
// of its children). A block is *smooth* when
//   - these nine samples hit the same material slot and the same plane (unit normals within
//     10⁻⁶, plane offsets n·p within 1 mm), of a glossy material, and have the same *reuse
//     class* ≥ 0 (the caller's: the renderer gives every sample of a rough material class 0, and
//     a near-mirror sample, whose reflection keeps the scene's sharp edges, class 1 or 2 only
//     when its lobe window is wholly open or wholly closed sky — specular_sky.h,
//     lobe_window_sky: no visibility edge anywhere near its reflection — else −1, never
//     interpolated), and
//   - the corners' bilinear interpolation predicts the five marched check points within
//     `tolerance` of the largest magnitude involved, in each of X, Y and Z: an a-posteriori
//     check of the interpolation error where it is largest for a smooth term, in both axes.
// In a smooth block, the samples on the same plane with the centre's class take the bilinear
// interpolation of the corners and all others are marched exactly; a block that is not smooth is
// split in four. A 4 × 4 block that is not smooth tries its upper and lower 4 × 2 halves (else
// its left and right 2 × 4 halves) as blocks of their own — corners and long-edge midpoints on
// its lattice of marched points, plus the half's centre, marched as a check across its short
// side — so that where a window edge crosses a block of wall the wall half is still
// interpolated; whatever no half interpolates is marched exactly. Blocks overhanging the image's
// right or bottom edge are never smooth (their outside corners have no sample) and are split.
// Deterministic (decisions use computed values only) and independent of the thread count.
// block ≤ 1 or tolerance ≤ 0: every sample exactly.
// What it costs in accuracy is measured against exact shading in bench_render (max and mean
// deviation over the figure) and bounded in renderer_test.
#include <cstdint>
#include <functional>
#include <vector>

#include "lighting/spectrum/colour.h"
#include "render/renderer.h"

namespace skyband {

struct SpecularReuseStats {
  std::size_t exact = 0, interpolated = 0;
};

// out[k] = specular sky XYZ of surface k for every k with glossy(k) (others left untouched).
// `exact(k)` marches surface k; `glossy(k)`: surface k has a specular term; `reuse_class(k)`:
// its reuse class (above; < 0: always marched).
SpecularReuseStats shade_specular_with_reuse(const GeometryPass& pass, int block, double tolerance,
                                             const std::function<bool(std::size_t)>& glossy,
                                             const std::function<int(std::size_t)>& reuse_class,
                                             const std::function<Xyz(std::size_t)>& exact, int threads, std::vector<Xyz>& out);

}  // namespace skyband
