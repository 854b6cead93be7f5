#include "cli/contact_sheet.h"

#include <algorithm>
#include <cctype>
#include <cstdint>

namespace skyband::cli {
namespace {

// 5×7 glyphs, one string of 7 rows per glyph, '#' = ink. Drawn for skyband (no external font).
struct Glyph {
  char c;
  const char* rows[7];
};
constexpr Glyph kFont[] = {
    {'A', {".###.", "#...#", "#...#", "#####", "#...#", "#...#", "#...#"}},
    {'B', {"####.", "#...#", "#...#", "####.", "#...#", "#...#", "####."}},
    {'C', {".###.", "#...#", "#....", "#....", "#....", "#...#", ".###."}},
    {'D', {"####.", "#...#", "#...#", "#...#", "#...#", "#...#", "####."}},
    {'E', {"#####", "#....", "#....", "####.", "#....", "#....", "#####"}},
    {'F', {"#####", "#....", "#....", "####.", "#....", "#....", "#...."}},
    {'G', {".###.", "#...#", "#....", "#.###", "#...#", "#...#", ".####"}},
    {'H', {"#...#", "#...#", "#...#", "#####", "#...#", "#...#", "#...#"}},
    {'I', {".###.", "..#..", "..#..", "..#..", "..#..", "..#..", ".###."}},
    {'J', {"..###", "...#.", "...#.", "...#.", "...#.", "#..#.", ".##.."}},
    {'K', {"#...#", "#..#.", "#.#..", "##...", "#.#..", "#..#.", "#...#"}},
    {'L', {"#....", "#....", "#....", "#....", "#....", "#....", "#####"}},
    {'M', {"#...#", "##.##", "#.#.#", "#.#.#", "#...#", "#...#", "#...#"}},
    {'N', {"#...#", "#...#", "##..#", "#.#.#", "#..##", "#...#", "#...#"}},
    {'O', {".###.", "#...#", "#...#", "#...#", "#...#", "#...#", ".###."}},
    {'P', {"####.", "#...#", "#...#", "####.", "#....", "#....", "#...."}},
    {'Q', {".###.", "#...#", "#...#", "#...#", "#.#.#", "#..#.", ".##.#"}},
    {'R', {"####.", "#...#", "#...#", "####.", "#.#..", "#..#.", "#...#"}},
    {'S', {".####", "#....", "#....", ".###.", "....#", "....#", "####."}},
    {'T', {"#####", "..#..", "..#..", "..#..", "..#..", "..#..", "..#.."}},
    {'U', {"#...#", "#...#", "#...#", "#...#", "#...#", "#...#", ".###."}},
    {'V', {"#...#", "#...#", "#...#", "#...#", "#...#", ".#.#.", "..#.."}},
    {'W', {"#...#", "#...#", "#...#", "#.#.#", "#.#.#", "#.#.#", ".#.#."}},
    {'X', {"#...#", "#...#", ".#.#.", "..#..", ".#.#.", "#...#", "#...#"}},
    {'Y', {"#...#", "#...#", ".#.#.", "..#..", "..#..", "..#..", "..#.."}},
    {'Z', {"#####", "....#", "...#.", "..#..", ".#...", "#....", "#####"}},
    {'0', {".###.", "#...#", "#..##", "#.#.#", "##..#", "#...#", ".###."}},
    {'1', {"..#..", ".##..", "..#..", "..#..", "..#..", "..#..", ".###."}},
    {'2', {".###.", "#...#", "....#", "...#.", "..#..", ".#...", "#####"}},
    {'3', {"#####", "...#.", "..#..", "...#.", "....#", "#...#", ".###."}},
    {'4', {"...#.", "..##.", ".#.#.", "#..#.", "#####", "...#.", "...#."}},
    {'5', {"#####", "#....", "####.", "....#", "....#", "#...#", ".###."}},
    {'6', {"..##.", ".#...", "#....", "####.", "#...#", "#...#", ".###."}},
    {'7', {"#####", "....#", "...#.", "..#..", ".#...", ".#...", ".#..."}},
    {'8', {".###.", "#...#", "#...#", ".###.", "#...#", "#...#", ".###."}},
    {'9', {".###.", "#...#", "#...#", ".####", "....#", "...#.", ".##.."}},
    {'-', {".....", ".....", ".....", "#####", ".....", ".....", "....."}},
    {'.', {".....", ".....", ".....", ".....", ".....", ".##..", ".##.."}},
    {':', {".....", ".##..", ".##..", ".....", ".##..", ".##..", "....."}},
    {'/', {".....", "....#", "...#.", "..#..", ".#...", "#....", "....."}},
    {'(', {"...#.", "..#..", ".#...", ".#...", ".#...", "..#..", "...#."}},
    {')', {".#...", "..#..", "...#.", "...#.", "...#.", "..#..", ".#..."}},
    {'%', {"##...", "##..#", "...#.", "..#..", ".#...", "#..##", "...##"}},
    {'*', {".##..", "#..#.", "#..#.", ".##..", ".....", ".....", "....."}},  // degree sign
};

const Glyph* glyph_of(char c) {
  c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  for (const Glyph& g : kFont)
    if (g.c == c) return &g;
  return nullptr;
}

}  // namespace

int text_width(const std::string& text, int scale) {
  return static_cast<int>(text.size()) * 6 * scale;
}

void draw_text(SheetImage& img, int x, int y, const std::string& text, float level, int scale) {
  for (std::size_t i = 0; i < text.size(); ++i) {
    // UTF-8 "°" (0xC2 0xB0) is drawn with the degree glyph '*'.
    char c = text[i];
    if (static_cast<unsigned char>(c) == 0xC2 && i + 1 < text.size() && static_cast<unsigned char>(text[i + 1]) == 0xB0) {
      c = '*';
    }
    const Glyph* g = glyph_of(c);
    const int gx = x + 6 * scale * static_cast<int>(i);
    if (g)
      for (int r = 0; r < 7; ++r)
        for (int col = 0; col < 5; ++col) {
          if (g->rows[r][col] != '#') continue;
          for (int sy = 0; sy < scale; ++sy)
            for (int sx = 0; sx < scale; ++sx) {
              const int px = gx + col * scale + sx, py = y + r * scale + sy;
              if (px < 0 || py < 0 || px >= img.width || py >= img.height) continue;
              float* p =
                  &img.rgb[(static_cast<std::size_t>(py) * static_cast<std::size_t>(img.width) + static_cast<std::size_t>(px)) *
                           3];
              p[0] = p[1] = p[2] = level;
            }
        }
  }
}

SheetImage make_contact_sheet(const std::vector<SheetTile>& tiles, int columns) {
  constexpr int kScale = 2, kMargin = 8, kLabel = 7 * kScale + 6;
  SheetImage s;
  if (tiles.empty() || columns < 1) return s;
  int tw = 0, th = 0;
  for (const SheetTile& t : tiles) {
    tw = std::max(tw, t.width);
    th = std::max(th, t.height);
  }
  const int cols = std::min<int>(columns, static_cast<int>(tiles.size()));
  const int rows = (static_cast<int>(tiles.size()) + cols - 1) / cols;
  s.width = kMargin + cols * (tw + kMargin);
  s.height = kMargin + rows * (kLabel + th + kMargin);
  // Background: linear 0.02 (dark grey after tone mapping).
  s.rgb.assign(static_cast<std::size_t>(s.width) * static_cast<std::size_t>(s.height) * 3, 0.02f);
  // One label scale for the whole sheet: 2× only if every label fits its tile at 2×.
  int scale = kScale;
  for (const SheetTile& t : tiles)
    if (text_width(t.label, kScale) > tw) scale = 1;
  for (std::size_t k = 0; k < tiles.size(); ++k) {
    const SheetTile& t = tiles[k];
    const int cx = kMargin + static_cast<int>(k % static_cast<std::size_t>(cols)) * (tw + kMargin);
    const int cy = kMargin + static_cast<int>(k / static_cast<std::size_t>(cols)) * (kLabel + th + kMargin);
    // Linear 50 maps to white (ACES fit saturates: tone value > 0.99). Labels wider than the
    // tile are cut at the tile's edge.
    const std::size_t fit = static_cast<std::size_t>(std::max(0, tw / (6 * scale)));
    draw_text(s, cx, cy + (kScale - scale) * 7, t.label.substr(0, std::min(fit, t.label.size())), 50.0f, scale);
    for (int y = 0; y < t.height; ++y)
      for (int x = 0; x < t.width; ++x)
        for (int c = 0; c < 3; ++c)
          s.rgb[((static_cast<std::size_t>(cy + kLabel + y)) * static_cast<std::size_t>(s.width) +
                 static_cast<std::size_t>(cx + x)) *
                    3 +
                static_cast<std::size_t>(c)] =
              static_cast<float>(
                  t.rgb[(static_cast<std::size_t>(y) * static_cast<std::size_t>(t.width) + static_cast<std::size_t>(x)) * 3 +
                        static_cast<std::size_t>(c)] *
                  t.exposure);
  }
  return s;
}

}  // namespace skyband::cli
