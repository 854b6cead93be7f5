#pragma once
// Text on 8-bit RGB pictures (legends, compass labels): a 5 × 7 pixel font of the digits,
// upper-case letters (lower case is drawn upper case) and . , - + ( ) / : _ = % [ ], each glyph
// pixel drawn as a scale × scale square; glyphs advance by 6 glyph pixels.
#include <cstdint>
#include <string_view>
#include <vector>

namespace skyband::cli {

struct Rgb8 {
  std::uint8_t r = 0, g = 0, b = 0;
};

// An 8-bit RGB picture, rows top to bottom, interleaved.
struct Picture {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
  Picture(int w, int h, Rgb8 fill);
  // Clipped to the picture.
  void put(int x, int y, Rgb8 c);
  void fill_rect(int x0, int y0, int x1, int y1, Rgb8 c);  // [x0, x1) × [y0, y1)
};

// Width in picture pixels of `text` at `scale`.
int text_width(std::string_view text, int scale);
constexpr int text_height(int scale) {
  return 7 * scale;
}

// Draws `text` with its top-left corner at (x, y); characters without a glyph are drawn as
// spaces. With `outline`, every glyph pixel is first surrounded by a one-pixel border of that
// colour (legible on any background).
void draw_text(Picture& p, int x, int y, std::string_view text, int scale, Rgb8 colour, const Rgb8* outline = nullptr);

}  // namespace skyband::cli
