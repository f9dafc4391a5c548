// scansurf: exact CPU rasterization of one feature's contours, pixel for pixel what the GPU
// draws (Vulkan's top-left rule at the device's sub-pixel precision; see pixel_runs.h).
#include "geometry/overlaps/pixel_runs.h"

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <utility>

#include "geometry/overlaps/raster_rules.h"

namespace scansurf {
namespace {

using I64 = std::int64_t;

// Floor and ceiling of n / d for d > 0.
I64 floorDiv(I64 n, I64 d) { return n >= 0 ? n / d : -((-n + d - 1) / d); }
I64 ceilDiv(I64 n, I64 d) { return -floorDiv(-n, d); }

struct Crossing {
  int row;
  I64 column;  // first pixel whose centre is at or right of the crossing
};

// Every crossing of the edge a -> b with the rows' centre lines, half-open in v.
void addCrossings(SubpixelPoint a, SubpixelPoint b, int bits, const Grid& grid, std::vector<Crossing>& out) {
  if (a.v == b.v) return;  // horizontal: never counted
  if (a.v > b.v) std::swap(a, b);
  const I64 one = I64{1} << bits, half = one >> 1;
  // Rows with a.v <= centre < b.v, clipped to the grid.
  const I64 first = std::max<I64>(0, ceilDiv(a.v - half, one));
  const I64 last = std::min<I64>(grid.ny - 1, ceilDiv(b.v - half, one) - 1);
  const I64 du = b.u - a.u, dv = b.v - a.v;
  for (I64 j = first; j <= last; ++j) {
    const I64 v = j * one + half;
    // Crossing at u = a.u + (v - a.v) du / dv; centre i counts it when u <= i*one + half.
    const I64 numerator = (a.u - half) * dv + (v - a.v) * du;
    out.push_back({static_cast<int>(j), ceilDiv(numerator, dv * one)});
  }
}

}  // namespace

std::vector<PixelRun> rasterizeSlice(const std::vector<Contour>& contours, const Grid& grid, int subPixelBits) {
  std::vector<Crossing> crossings;
  for (const Contour& c : contours) {
    const std::size_t n = c.points.size();
    if (n < 3) continue;
    SubpixelPoint previous = toSubpixel(grid, c.points[n - 1].x, c.points[n - 1].y, subPixelBits);
    for (const Point2& p : c.points) {
      const SubpixelPoint current = toSubpixel(grid, p.x, p.y, subPixelBits);
      addCrossings(previous, current, subPixelBits, grid, crossings);
      previous = current;
    }
  }
  std::sort(crossings.begin(), crossings.end(),
            [](const Crossing& x, const Crossing& y) { return x.row != y.row ? x.row < y.row : x.column < y.column; });
  std::vector<PixelRun> runs;
  for (std::size_t c = 0; c + 1 < crossings.size(); c += 2) {
    // Each row holds an even number of crossings (closed contours): pair them up.
    const Crossing& in = crossings[c];
    const Crossing& out = crossings[c + 1];
    const I64 begin = std::max<I64>(0, in.column), end = std::min<I64>(grid.nx, out.column);
    if (begin >= end) continue;
    if (!runs.empty() && runs.back().row == in.row && runs.back().end >= begin)
      runs.back().end = std::max(runs.back().end, static_cast<int>(end));
    else
      runs.push_back({in.row, static_cast<int>(begin), static_cast<int>(end)});
  }
  return runs;
}

namespace {

// Calls shared(run) for each run of pixels in both lists, in order.
template <typename Shared>
void forEachSharedRun(const std::vector<PixelRun>& a, const std::vector<PixelRun>& b, Shared&& shared) {
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (a[i].row != b[j].row) {
      (a[i].row < b[j].row ? i : j)++;
      continue;
    }
    const int lo = std::max(a[i].begin, b[j].begin), hi = std::min(a[i].end, b[j].end);
    if (hi > lo) shared(PixelRun{a[i].row, lo, hi});
    (a[i].end < b[j].end ? i : j)++;
  }
}

}  // namespace

std::size_t sharedPixels(const std::vector<PixelRun>& a, const std::vector<PixelRun>& b) {
  std::size_t shared = 0;
  forEachSharedRun(a, b, [&](const PixelRun& r) { shared += static_cast<std::size_t>(r.end - r.begin); });
  return shared;
}

std::vector<PixelRun> intersectPixelRuns(const std::vector<PixelRun>& a, const std::vector<PixelRun>& b) {
  std::vector<PixelRun> out;
  forEachSharedRun(a, b, [&](const PixelRun& r) { out.push_back(r); });
  return out;
}

bool coversPixel(const std::vector<PixelRun>& runs, int column, int row) {
  // The first run past (row, column); the one before it holds the pixel if any does.
  const auto after = std::upper_bound(
      runs.begin(), runs.end(), std::pair{row, column},
      [](const std::pair<int, int>& p, const PixelRun& r) { return p.first != r.row ? p.first < r.row : p.second < r.begin; });
  if (after == runs.begin()) return false;
  const PixelRun& r = *std::prev(after);
  return r.row == row && column >= r.begin && column < r.end;
}

bool touchInPlane(const std::vector<PixelRun>& a, const std::vector<PixelRun>& b) {
  // Runs of b grown by one pixel along the row touch a on the same row; unchanged runs of b
  // on the rows above and below touch a when they overlap in columns.
  for (int dRow : {-1, 0, 1}) {
    std::vector<PixelRun> shifted;
    shifted.reserve(b.size());
    const int grow = dRow == 0 ? 1 : 0;
    for (const PixelRun& r : b) shifted.push_back({r.row + dRow, r.begin - grow, r.end + grow});
    if (sharedPixels(a, shifted) > 0) return true;
  }
  return false;
}

std::vector<PixelRun> unitePixelRuns(const std::vector<PixelRun>& a, const std::vector<PixelRun>& b) {
  std::vector<PixelRun> all(a);
  all.insert(all.end(), b.begin(), b.end());
  std::sort(all.begin(), all.end(),
            [](const PixelRun& x, const PixelRun& y) { return x.row != y.row ? x.row < y.row : x.begin < y.begin; });
  std::vector<PixelRun> out;
  for (const PixelRun& r : all) {
    if (!out.empty() && out.back().row == r.row && out.back().end >= r.begin)
      out.back().end = std::max(out.back().end, r.end);
    else
      out.push_back(r);
  }
  return out;
}

std::size_t pixelCount(const std::vector<PixelRun>& runs) {
  std::size_t n = 0;
  for (const PixelRun& r : runs) n += static_cast<std::size_t>(r.end - r.begin);
  return n;
}

}  // namespace scansurf
