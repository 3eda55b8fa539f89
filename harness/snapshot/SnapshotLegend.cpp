#include "harness/snapshot/SnapshotLegend.h"

#include <algorithm>
#include <optional>

#include "render/ImageText.h"

namespace cdb {

namespace {

constexpr Rgb kBand{250, 250, 250};
constexpr Rgb kRule{200, 200, 200};
constexpr Rgb kText{30, 30, 30};

struct Metrics {
  int scale, pad, line, box, gap;
};

Metrics metricsFor(int width) {
  const int s = width >= 720 ? 2 : 1;
  return {s, 6 * s, textLineHeight(s), 8 * s, 14 * s};
}

int swatchWidth(const LegendSwatch& w, const Metrics& m) {
  const int box = w.style == LegendSwatch::Style::None ? 0 : m.box + 4 * m.scale;
  return box + textWidth(w.label, m.scale);
}

// Places `swatches` in rows from height `y`, wrapping at the band's width; nothing when they do
// not all fit above maxHeight. Returns the height below the last row.
std::optional<int> flow(const std::vector<LegendSwatch>& swatches, int y, int width, int maxHeight,
                        const Metrics& m, std::vector<LegendLayout::Placed>& placed) {
  placed.clear();
  int x = m.pad;
  for (const LegendSwatch& s : swatches) {
    const int w = swatchWidth(s, m);
    if (x > m.pad && x + w > width - m.pad) {
      y += m.line;
      x = m.pad;
    }
    if (x + w > width - m.pad || y + m.line + m.pad > maxHeight) return std::nullopt;
    placed.push_back({x, y, s});
    x += w + m.gap;
  }
  return swatches.empty() ? y : y + m.line;
}

// `line` in pieces no wider than `width` at the metrics' scale, broken after spaces (a word wider
// than that on its own is cut between letters).
std::vector<std::string> wrapped(const std::string& line, int width, const Metrics& m) {
  std::vector<std::string> out;
  std::string rest = line;
  while (textWidth(rest, m.scale) > width) {
    std::size_t fits = 1;  // the longest prefix that fits (at least one letter)
    while (fits < rest.size() && textWidth(rest.substr(0, fits + 1), m.scale) <= width) ++fits;
    const std::size_t space = rest.rfind(' ', fits);
    const std::size_t cut = space != std::string::npos && space > 0 ? space : fits;
    out.push_back(rest.substr(0, cut));
    rest = rest.substr(cut < rest.size() && rest[cut] == ' ' ? cut + 1 : cut);
  }
  out.push_back(rest);
  return out;
}

}  // namespace

LegendLayout layoutLegend(const LegendContent& content, int width, int maxHeight) {
  const Metrics m = metricsFor(width);
  LegendLayout out;
  out.width = width;
  out.scale = m.scale;
  int y = m.pad;
  for (const std::string& line : content.lines) {
    for (const std::string& piece : wrapped(line, width - 2 * m.pad, m)) {
      if (y + m.line + m.pad > maxHeight) break;
      out.lines.emplace_back(y, piece);
      y += m.line;
    }
  }
  // All the swatches, or as many as fit with "+N more" after them.
  std::optional<int> end = flow(content.swatches, y, width, maxHeight, m, out.swatches);
  for (std::size_t keep = content.swatches.size(); !end && keep-- > 0;) {
    std::vector<LegendSwatch> shown(content.swatches.begin(), content.swatches.begin() + keep);
    // Appended, not "+" + ...: GCC 12 warns falsely (-Wrestrict) on a literal plus a temporary.
    std::string more = std::to_string(content.swatches.size() - keep);
    more.insert(more.begin(), '+');
    more += " more";
    shown.push_back({kText, more, LegendSwatch::Style::None});
    end = flow(shown, y, width, maxHeight, m, out.swatches);
  }
  if (!end) out.swatches.clear();
  out.height = maxHeight;
  return out;
}

int legendBandHeight(int width) {
  const Metrics m = metricsFor(width);
  return 2 * m.pad + 4 * m.line;
}

void drawLegend(RgbImage& image, int top, const LegendLayout& layout) {
  const Metrics m = metricsFor(layout.width);
  fillRect(image, 0, top, layout.width, layout.height, kBand);
  fillRect(image, 0, top, layout.width, layout.scale, kRule);
  // stb_easy_font's glyphs sit in the upper 7 of a line's 12 units: centre them a little.
  const int textDrop = 2 * m.scale;
  for (const auto& [y, text] : layout.lines)
    drawText(image, m.pad, top + y + textDrop, text, m.scale, kText);
  for (const LegendLayout::Placed& p : layout.swatches) {
    const int bx = p.x, by = top + p.y + textDrop - m.scale;
    int tx = p.x;
    if (p.swatch.style != LegendSwatch::Style::None) {
      fillRect(image, bx, by, m.box, m.box, p.swatch.colour);
      tx += m.box + 4 * m.scale;
    }
    if (p.swatch.style == LegendSwatch::Style::Frame)
      fillRect(image, bx + 2 * m.scale, by + 2 * m.scale, m.box - 4 * m.scale, m.box - 4 * m.scale,
               kBand);
    drawText(image, tx, top + p.y + textDrop, p.swatch.label, m.scale, kText);
  }
}

}  // namespace cdb
