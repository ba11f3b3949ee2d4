#pragma once
// Writes plain ASCII DXF drawings for tests, independently of dxflib (as
// tests/tools/make_dxf.py does): a header with $INSUNITS and LINE entities, each with its
// own handle (from 100 hex up), so that tests can generate drawings of any size.

#include <cstdio>
#include <fstream>
#include <string>

namespace ccbuild::testing {

class DxfWriter {
 public:
  explicit DxfWriter(int insunits) : insunits_(insunits) {}

  /// A LINE on `layer` from (x1, y1) to (x2, y2), in the drawing's unit; returns its handle.
  int line(const std::string& layer, double x1, double y1, double x2, double y2) {
    char buffer[256];
    std::snprintf(buffer, sizeof buffer,
                  "0\nLINE\n5\n%X\n8\n%s\n10\n%.17g\n20\n%.17g\n11\n%.17g\n21\n%.17g\n", handle_,
                  layer.c_str(), x1, y1, x2, y2);
    entities_ += buffer;
    return handle_++;
  }
  /// The line of `handle`'s value in text() (a header of 18 lines, then 14 lines a LINE):
  /// where an error about that entity points.
  static int handle_line(int handle) { return 18 + 14 * (handle - 0x100) + 4; }

  std::string text() const {
    return "0\nSECTION\n2\nHEADER\n9\n$ACADVER\n1\nAC1015\n9\n$INSUNITS\n70\n" +
           std::to_string(insunits_) + "\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n" + entities_ +
           "0\nENDSEC\n0\nEOF\n";
  }
  void write(const std::string& path) const { std::ofstream(path, std::ios::binary) << text(); }

 private:
  int insunits_;
  int handle_ = 0x100;
  std::string entities_;
};

}  // namespace ccbuild::testing
