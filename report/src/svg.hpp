#pragma once
// A small SVG writer for the plan drawings: escaped text, text fitted to a width, axis
// ticks at round numbers, a scale bar and a legend. Internal to the report library.

#include <string>
#include <vector>

namespace ccbuild::report::svg {

/// Text made safe inside XML (&, <, >, quotes).
std::string escape(const std::string& text);

/// A number for an SVG attribute, 1 decimal.
std::string px(double value);

/// Roughly how wide `text` is at `font_px` in a sans-serif font, px.
double text_width_px(const std::string& text, double font_px);

/// `text` shortened with an ellipsis (from the left, keeping its end, when `keep_end`) so
/// that it fits `width_px` at `font_px`.
std::string fit(const std::string& text, double width_px, double font_px, bool keep_end = false);

/// Tick values at round steps (1, 2 or 5 times a power of ten) covering [lo, hi], about
/// `wanted` of them.
std::vector<double> ticks(double lo, double hi, int wanted);

/// A round length (1, 2 or 5 times a power of ten) near `about`.
double round_length(double about);

/// A tick label: the value with as many decimals as the step needs.
std::string tick_label(double value, double step);

class Document {
 public:
  Document(double width_px, double height_px);

  void text(double x, double y, const std::string& content, double font_px,
            const std::string& attributes = "");
  void raw(const std::string& element) { body_ += element; }
  /// A legend entry: a swatch (an SVG element drawn at (x, y) to (x + 24, y)) and its label.
  struct LegendItem {
    std::string swatch;  ///< "line", "dashed", "dot", "band"
    std::string colour;
    std::string label;
  };
  /// Draws the legend in a box at (x, y), items flowing into rows within `width_px`;
  /// returns its height.
  double legend(double x, double y, double width_px, const std::vector<LegendItem>& items);

  double width() const { return width_; }
  void set_height(double height_px) { height_ = height_px; }
  double height() const { return height_; }
  std::string str() const;

 private:
  double width_, height_;
  std::string body_;
};

}  // namespace ccbuild::report::svg
