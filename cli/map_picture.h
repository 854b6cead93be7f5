#pragma once
// The false-colour picture of a map (`skyband map --png`): the raster north up, values in the
// viridis colour map (perceptually uniform, legible in grey and to colour-blind readers), pixels
// without a value in light grey, and beside it a legend: the quantity and its units, a colour
// bar with labelled ticks over the range shown, the no-data swatch, the pixel size and the
// values' minimum, mean and maximum.
//
// Range: the values' minimum and maximum rounded outwards to multiples of 0.05 (a fraction of the
// open sky), so that maps of one city share tick labels; values are clamped to it.
// Size: the longer side of the map is drawn 400 to 1600 pixels long (nearest raster pixel per
// picture pixel; rasters longer than 1600 pixels are subsampled).
#include <span>
#include <string>

#include "cli/bitmap_font.h"

namespace skyband::cli {

struct MapPictureInput {
  std::size_t columns = 0, rows = 0;
  std::span<const float> values;  // row-major, row 0 the northernmost
  float nodata = -9999.0f;
  std::string quantity;  // "SKY VIEW FACTOR"
  std::string units;     // "FRACTION OF THE OPEN SKY"
  double pixel_m = 0;    // pixel size, metres (0: not shown)
};

// Viridis at t ∈ [0, 1] (clamped): linear interpolation of 9 samples of the colour map.
Rgb8 viridis(double t);

// The colour range described above; `lo` < `hi` always.
void map_range(std::span<const float> values, float nodata, double& lo, double& hi);

Picture map_picture(const MapPictureInput& in);

}  // namespace skyband::cli
