// The local intervals between a layer and the one under it (detail::interval_offsets): at
// the pieces' ends and where beads meet mid-piece, each side of a meeting on its own.

#include <gtest/gtest.h>

#include "schedule_deposits.hpp"

namespace ccbuild::schedule::detail {
namespace {

/// One wall, one piece from x = 0 to 4 m along y = 0.
floors::Layer one_piece() {
  floors::Layer l;
  l.points = {{0.0, 0.0}, {4.0, 0.0}};
  floors::LayerSegment s;
  s.wall_id = 7;
  s.start_point = 0;
  s.end_point = 1;
  s.length_m = 4.0;
  l.segments = {s};
  return l;
}

Span span(double x0, double x1, double t0, double t1) {
  return {Eigen::Vector2d(x0, 0.0), Eigen::Vector2d(x1, 0.0), t0, t1};
}

DepositIndex index_of_spans(std::vector<Span> spans) {
  DepositIndex index;
  index.spans[7] = std::move(spans);
  return index;
}

TEST(IntervalPoints, OneBeadOverOneBeadIsCheckedAtThePiecesEnds) {
  // Both layers laid left to right at 1 m/s: the interval is the same everywhere.
  const auto below = index_of_spans({span(0, 4, 0, 4)});
  const IntervalOffsets o = interval_offsets(one_piece(), below, below);
  EXPECT_EQ(o.ends, 2);
  EXPECT_DOUBLE_EQ(o.min_offset_s, 0.0);
  EXPECT_DOUBLE_EQ(o.max_offset_s, 0.0);
}

TEST(IntervalPoints, TheShortestIntervalMayLieWhereABeadBelowEndsMidPiece) {
  // Above: one nozzle from x = 0 to 4 m over 0-4 s. Below: nozzle 1 from x = 0 to 2 m
  // over 0-2 s, nozzle 2 from x = 4 m back to 2 m over 100-102 s. Left of x = 2 m the
  // layer above comes 0 s after the one below; right of it 2x - 104 s: -100 s at x = 2 m,
  // -96 s at x = 4 m. The pieces' ends alone (0 and -96 s) would miss the -100 s.
  const auto above = index_of_spans({span(0, 4, 0, 4)});
  const auto below = index_of_spans({span(0, 2, 0, 2), span(4, 2, 100, 102)});
  const IntervalOffsets o = interval_offsets(one_piece(), above, below);
  EXPECT_EQ(o.ends, 4) << "both piece ends, and the meeting point from each side";
  EXPECT_DOUBLE_EQ(o.min_offset_s, -100.0);
  EXPECT_NEAR(o.min_at.x_m, 2.0, 1e-12);
  EXPECT_DOUBLE_EQ(o.max_offset_s, 0.0);
  EXPECT_DOUBLE_EQ(o.max_at.x_m, 0.0);
}

TEST(IntervalPoints, BeadsMeetingMidPieceArePairedSideBySide) {
  // Both layers: nozzle 1 from x = 0 to 2 m over 0-2 s, nozzle 2 from 2 to 4 m over
  // 50-52 s. Every point is covered exactly as long after it was laid: 0 s. Pairing, at
  // x = 2 m, the bead above on one side with the bead below on the other would report
  // 48 s and -48 s.
  const auto both = index_of_spans({span(0, 2, 0, 2), span(2, 4, 50, 52)});
  const IntervalOffsets o = interval_offsets(one_piece(), both, both);
  EXPECT_EQ(o.ends, 4);
  EXPECT_DOUBLE_EQ(o.min_offset_s, 0.0);
  EXPECT_DOUBLE_EQ(o.max_offset_s, 0.0);
}

TEST(IntervalPoints, ABeadBesideThePieceOrOverAnOpeningIsNotCounted) {
  // Below, a bead of wall 7 off the piece's line by just over 2 mm, and one along a
  // collinear neighbour (x = 4 to 6 m): nothing under the piece, nothing checked. Within
  // 2 mm it counts.
  const auto above = index_of_spans({span(0, 4, 0, 4)});
  DepositIndex beside;
  beside.spans[7] = {{Eigen::Vector2d(0, 0.0021), Eigen::Vector2d(4, 0.0021), 0, 4},
                     span(4, 6, 0, 2)};
  EXPECT_EQ(interval_offsets(one_piece(), above, beside).ends, 0);
  beside.spans[7][0].a.y() = beside.spans[7][0].b.y() = 0.0019;
  EXPECT_EQ(interval_offsets(one_piece(), above, beside).ends, 2);
}

}  // namespace
}  // namespace ccbuild::schedule::detail
