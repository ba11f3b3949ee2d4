#include "svg.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ccbuild/common/format.hpp"

namespace ccbuild::report::svg {

std::string escape(const std::string& text) {
  return xml_escape(text);
}

std::string px(double value) {
  char text[64];
  std::snprintf(text, sizeof text, "%.1f", value);
  return text;
}

double text_width_px(const std::string& text, double font_px) {
  // A sans-serif font advances about 0.55 em a character on average, bold text more:
  // 0.62 em keeps fitted text inside. Count UTF-8 code points.
  std::size_t chars = 0;
  for (unsigned char c : text)
    if ((c & 0xC0) != 0x80) ++chars;
  return 0.62 * font_px * static_cast<double>(chars);
}

std::string fit(const std::string& text, double width_px, double font_px, bool keep_end) {
  if (text_width_px(text, font_px) <= width_px) return text;
  const std::string ellipsis = "...";
  std::size_t keep = static_cast<std::size_t>(
      std::max(0.0, width_px / (0.62 * font_px) - static_cast<double>(ellipsis.size())));
  keep = std::min(keep, text.size());
  // Do not cut a UTF-8 sequence in half.
  if (keep_end) {
    std::size_t from = text.size() - keep;
    while (from < text.size() && (static_cast<unsigned char>(text[from]) & 0xC0) == 0x80) ++from;
    return ellipsis + text.substr(from);
  }
  while (keep > 0 && (static_cast<unsigned char>(text[keep]) & 0xC0) == 0x80) --keep;
  return text.substr(0, keep) + ellipsis;
}

std::vector<double> ticks(double lo, double hi, int wanted) {
  std::vector<double> out;
  if (!(hi > lo) || wanted < 1) return {lo};
  const double step = round_length((hi - lo) / wanted);
  const double first = std::ceil(lo / step - 1e-9) * step;
  for (int k = 0; k < 1000; ++k) {
    const double v = first + k * step;
    if (v > hi + 1e-9 * step) break;
    out.push_back(std::abs(v) < 1e-12 * step ? 0.0 : v);
  }
  return out;
}

double round_length(double about) {
  if (!(about > 0.0) || !std::isfinite(about)) return 1.0;
  const double power = std::pow(10.0, std::floor(std::log10(about)));
  const double m = about / power;
  const double nice = m < 1.5 ? 1.0 : m < 3.5 ? 2.0 : m < 7.5 ? 5.0 : 10.0;
  return nice * power;
}

std::string tick_label(double value, double step) {
  const int decimals = step >= 1.0 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", std::clamp(decimals, 0, 6), value);
  return text;
}

Document::Document(double width_px, double height_px) : width_(width_px), height_(height_px) {}

void Document::text(double x, double y, const std::string& content, double font_px,
                    const std::string& attributes) {
  body_ += "<text x=\"" + px(x) + "\" y=\"" + px(y) + "\" font-family=\"sans-serif\" font-size=\"" +
           px(font_px) + "\"" + (attributes.empty() ? "" : " " + attributes) + ">" +
           escape(content) + "</text>\n";
}

double Document::legend(double x, double y, double width_px, const std::vector<LegendItem>& items) {
  const double font = 12.0, row = 20.0, pad = 8.0;
  std::string group = "<g id=\"legend\">\n";
  double cx = x + pad, cy = y + pad + row / 2;
  int rows = 1;
  for (const auto& item : items) {
    const double w = 30.0 + text_width_px(item.label, font) + 16.0;
    if (cx + w > x + width_px - pad && cx > x + pad) {
      cx = x + pad;
      cy += row;
      ++rows;
    }
    const std::string c = escape(item.colour);
    if (item.swatch == "dot") {
      group +=
          "<circle cx=\"" + px(cx + 12) + "\" cy=\"" + px(cy) + "\" r=\"5\" fill=\"" + c + "\"/>\n";
    } else if (item.swatch == "band") {
      group += "<rect x=\"" + px(cx) + "\" y=\"" + px(cy - 6) +
               "\" width=\"24\" height=\"12\" fill=\"" + c + "\" fill-opacity=\"0.25\"/>\n";
    } else {
      group += "<line x1=\"" + px(cx) + "\" y1=\"" + px(cy) + "\" x2=\"" + px(cx + 24) +
               "\" y2=\"" + px(cy) + "\" stroke=\"" + c + "\" stroke-width=\"" +
               (item.swatch == "dashed" ? "1.5\" stroke-dasharray=\"5,4" : "4") + "\"/>\n";
    }
    group += "<text x=\"" + px(cx + 30) + "\" y=\"" + px(cy + 4) +
             "\" font-family=\"sans-serif\" font-size=\"" + px(font) + "\">" + escape(item.label) +
             "</text>\n";
    cx += w;
  }
  const double height = rows * row + 2 * pad;
  body_ += "<rect x=\"" + px(x) + "\" y=\"" + px(y) + "\" width=\"" + px(width_px) +
           "\" height=\"" + px(height) + "\" fill=\"#fafafa\" stroke=\"#ccc\"/>\n" + group +
           "</g>\n";
  return height;
}

std::string Document::str() const {
  return "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + px(width_) + "\" height=\"" +
         px(height_) + "\" viewBox=\"0 0 " + px(width_) + " " + px(height_) +
         "\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n" + body_ + "</svg>\n";
}

}  // namespace ccbuild::report::svg
