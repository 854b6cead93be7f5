#pragma once
// A labelled contact sheet of rendered images, assembled in linear RGB so that it can be written
// with the same tone curve as every preview (io/png_writer.h): each tile is its image's linear
// `total` layer multiplied by that image's exposure, and the sheet is written with exposure 1.
// Labels use a built-in 5×7 bitmap font (ours; upper-case letters, digits and - . : / ( ) % °
// — lower-case text is drawn in upper case, other characters as blanks), drawn at 2× scale.
#include <string>
#include <vector>

namespace skyband::cli {

struct SheetTile {
  int width = 0, height = 0;
  std::vector<float> rgb;  // linear, width·height·3
  double exposure = 1;     // applied to rgb when placed
  std::string label;
};

struct SheetImage {
  int width = 0, height = 0;
  std::vector<float> rgb;  // linear, already exposed: write with exposure 1
};

// Tiles in rows of `columns`, each with its label above it.
SheetImage make_contact_sheet(const std::vector<SheetTile>& tiles, int columns);

// Draws text at (x, y) (top-left, pixels) with a linear value `level` per channel; scale ≥ 1.
void draw_text(SheetImage& img, int x, int y, const std::string& text, float level, int scale);

// Width in pixels of text drawn at `scale` (6 columns per glyph including spacing).
int text_width(const std::string& text, int scale);

}  // namespace skyband::cli
