// scansurf: validation and normalization of the contour model (paper §3.2's input: features,
// their slices, closed contours of (x, y) points).
#include "geometry/contours/validate.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

#include "geometry/contours/crossings.h"
#include "scansurf/grid.h"
#include "scansurf/input.h"
#include "scansurf/label_volume.h"

namespace scansurf {

std::string formatNumber(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

namespace {

std::string sourceName(const ContourSet& contours) {
  return contours.source.empty() ? std::string("<contours>") : contours.source;
}

std::string describeContour(const ContourSet& contours, int feature, int slice, double z, int contour) {
  return describeSlice(contours, feature, slice, z) + ", contour " + std::to_string(contour);
}

Unexpected invalid(std::string message) { return makeError(Errc::InvalidInput, std::move(message)); }

bool samePoint(Point2 a, Point2 b) { return a.x == b.x && a.y == b.y; }

// Drops consecutive duplicates and trailing copies of the first point.
void dropRepeatedPoints(Contour& contour) {
  auto& pts = contour.points;
  pts.erase(std::unique(pts.begin(), pts.end(), samePoint), pts.end());
  while (pts.size() > 1 && samePoint(pts.front(), pts.back())) pts.pop_back();
}

std::size_t countDistinct(const Contour& contour) {
  std::vector<Point2> pts = contour.points;
  auto less = [](Point2 a, Point2 b) { return a.x != b.x ? a.x < b.x : a.y < b.y; };
  std::sort(pts.begin(), pts.end(), less);
  return static_cast<std::size_t>(std::unique(pts.begin(), pts.end(), samePoint) - pts.begin());
}

// Whether b is a's closed polyline point for point, from any start and in either direction.
bool sameLoop(const Contour& a, const Contour& b) {
  const std::size_t n = a.points.size();
  if (b.points.size() != n) return false;
  for (std::size_t start = 0; start < n; ++start) {
    if (!samePoint(a.points[0], b.points[start])) continue;
    for (const bool forward : {true, false}) {
      std::size_t i = 1;
      while (i < n && samePoint(a.points[i], b.points[forward ? (start + i) % n : (start + n - i) % n])) ++i;
      if (i == n) return true;
    }
  }
  return false;
}

// A contour that repeats another of its slice point for point (an exporter's duplicate) is
// dropped with a warning: by the even-odd rule the two copies would cancel and empty the region.
void dropRepeatedContours(ContourSet& contours, int f, FeatureSlice& slice, int s) {
  std::vector<Contour> kept;
  for (int c = 0; c < static_cast<int>(slice.contours.size()); ++c) {
    Contour& contour = slice.contours[static_cast<std::size_t>(c)];
    if (std::none_of(kept.begin(), kept.end(), [&](const Contour& k) { return sameLoop(k, contour); })) {
      kept.push_back(std::move(contour));
      continue;
    }
    contours.warnings.push_back(describeSlice(contours, f, s, slice.z) + ": contour " + std::to_string(c) +
                                " repeats an earlier contour of the slice point for point; the copy is dropped "
                                "(two copies would cancel by the even-odd rule)");
  }
  slice.contours = std::move(kept);
}

// A contour that crosses itself is filled as the even-odd rule has it (a spiral or a figure
// eight keeps only its odd-covered parts): said, with where, since it is rarely what was meant.
void warnAboutSelfCrossings(ContourSet& contours, int f, const FeatureSlice& slice, int s) {
  for (std::size_t c = 0; c < slice.contours.size(); ++c)
    if (const std::optional<Point2> at = firstSelfCrossing(slice.contours[c]))
      contours.warnings.push_back(describeSlice(contours, f, s, slice.z) + ": contour " + std::to_string(c) +
                                  " crosses itself (near x " + formatNumber(at->x) + ", y " + formatNumber(at->y) +
                                  "); its inside is what the even-odd rule encloses");
}

// The largest magnitude of the set's coordinates: differences below 1e-12 of it are rounding
// of one value, not a spacing.
double magnitudeOf(const ContourSet& contours) {
  double m = 0;
  for (const Feature& f : contours.features)
    for (const FeatureSlice& s : f.slices) {
      m = std::max(m, std::abs(s.z));
      for (const Contour& c : s.contours)
        for (const Point2& p : c.points) m = std::max({m, std::abs(p.x), std::abs(p.y)});
    }
  return m;
}

// Sorted gaps between consecutive distinct values above `noise`.
void appendGaps(std::vector<double> z, double noise, std::vector<double>& gaps) {
  std::sort(z.begin(), z.end());
  for (std::size_t i = 1; i < z.size(); ++i)
    if (z[i] - z[i - 1] > noise) gaps.push_back(z[i] - z[i - 1]);
}

// kRelativeSliceTolerance of the median gap between a feature's own planes (the slice spacing
// the data was drawn at, whatever its unit), or of the set's planes when no feature has two.
// A fixed tolerance merged 5 nm sections in metres into one plane and kept copies of a plane
// written 1e-9 apart in mm as two.
double planeToleranceOf(const ContourSet& contours) {
  const double noise = 1e-12 * magnitudeOf(contours);
  std::vector<double> gaps, all;
  for (const Feature& f : contours.features) {
    std::vector<double> z;
    for (const FeatureSlice& s : f.slices) z.push_back(s.z);
    all.insert(all.end(), z.begin(), z.end());
    appendGaps(std::move(z), noise, gaps);
  }
  if (gaps.empty()) appendGaps(std::move(all), noise, gaps);
  if (gaps.empty()) return std::max(noise, std::numeric_limits<double>::min());  // one plane
  std::nth_element(gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
  return std::max(kRelativeSliceTolerance * gaps[gaps.size() / 2], noise);
}

// Puts every slice within planeTolerance of a plane onto that plane's z (the lowest of its
// group), across features, so that later stages compare planes exactly. Merging distinct
// values is worth a warning: the slices may have been meant as planes of their own.
void snapToSharedPlanes(ContourSet& contours) {
  const std::vector<double> planes = contourPlanes(contours, contours.planeTolerance);
  std::vector<double> moved;  // the distinct positions that merged, for the warning
  double firstTo = 0;
  for (Feature& f : contours.features)
    for (FeatureSlice& s : f.slices) {
      const double plane = *(std::upper_bound(planes.begin(), planes.end(), s.z) - 1);  // its group's lowest z
      if (plane == s.z) continue;
      if (moved.empty()) firstTo = plane;
      moved.push_back(s.z);
      s.z = plane;
    }
  if (moved.empty()) return;
  const double firstFrom = moved.front();
  std::sort(moved.begin(), moved.end());
  moved.erase(std::unique(moved.begin(), moved.end()), moved.end());
  contours.warnings.push_back(sourceName(contours) + ": " + std::to_string(moved.size()) + " slice position(s) within " +
                              formatNumber(contours.planeTolerance) + " " + contours.units +
                              " (a thousandth of the median slice spacing) of a lower one were merged into its plane, e.g. z=" +
                              formatNumber(firstFrom) + " into z=" + formatNumber(firstTo));
}

// Slices of one feature on one plane combine: sorted by z (stable, so contours keep their
// input order), equal z joined.
void mergeSlicesOfOnePlane(Feature& feature) {
  std::stable_sort(feature.slices.begin(), feature.slices.end(),
                   [](const FeatureSlice& a, const FeatureSlice& b) { return a.z < b.z; });
  std::vector<FeatureSlice> merged;
  for (FeatureSlice& slice : feature.slices) {
    if (!merged.empty() && slice.z == merged.back().z) {
      auto& into = merged.back().contours;
      into.insert(into.end(), std::make_move_iterator(slice.contours.begin()), std::make_move_iterator(slice.contours.end()));
    } else {
      merged.push_back(std::move(slice));
    }
  }
  feature.slices = std::move(merged);
}

}  // namespace

std::string describeFeature(const ContourSet& contours, int feature) {
  return sourceName(contours) + ": feature \"" + contours.features[feature].name + "\" (#" + std::to_string(feature) + ")";
}

std::string describeSlice(const ContourSet& contours, int feature, int slice, double z) {
  return describeFeature(contours, feature) + ", slice z=" + formatNumber(z) + " (#" + std::to_string(slice) + ")";
}

Result<void> validateContours(ContourSet& contours) { return validateAndNormalize(contours); }

Result<void> validateAndNormalize(ContourSet& contours) {
  const std::string source = sourceName(contours);
  const int featureCount = static_cast<int>(contours.features.size());
  if (featureCount == 0) return invalid(source + ": no features");
  if (featureCount > kMaxFeatures)
    return invalid(source + ": " + std::to_string(featureCount) + " features, more than the " + std::to_string(kMaxFeatures) +
                   " supported");

  // A NUL ends a string in C, XML and DICOM readers: a name or unit holding one would be read
  // back as another (VTK's XML readers crash on it).
  if (contours.units.find('\0') != std::string::npos) return invalid(source + ": the units hold a NUL character");
  std::map<std::string, int> firstIndexOfName;
  for (int f = 0; f < featureCount; ++f) {
    const std::string& name = contours.features[f].name;
    if (name.empty()) return invalid(source + ": feature #" + std::to_string(f) + " has an empty name");
    if (name.find('\0') != std::string::npos)
      return invalid(source + ": feature #" + std::to_string(f) + " has a NUL character in its name");
    const auto [it, inserted] = firstIndexOfName.emplace(name, f);
    if (!inserted) return invalid(describeFeature(contours, f) + ": duplicate name, also feature #" + std::to_string(it->second));
  }

  for (int f = 0; f < featureCount; ++f) {
    Feature& feature = contours.features[f];
    for (int s = 0; s < static_cast<int>(feature.slices.size()); ++s) {
      FeatureSlice& slice = feature.slices[s];
      if (!std::isfinite(slice.z))
        return invalid(describeFeature(contours, f) + ", slice #" + std::to_string(s) + ": non-finite z");
      if (std::abs(slice.z) > kMaxCoordinate)
        return invalid(describeFeature(contours, f) + ", slice #" + std::to_string(s) + ": z = " + formatNumber(slice.z) +
                       " is beyond " + formatNumber(kMaxCoordinate) + " units from the origin");
      if (slice.contours.empty()) return invalid(describeSlice(contours, f, s, slice.z) + ": no contours");
      for (int c = 0; c < static_cast<int>(slice.contours.size()); ++c) {
        Contour& contour = slice.contours[c];
        for (std::size_t p = 0; p < contour.points.size(); ++p) {
          if (!std::isfinite(contour.points[p].x) || !std::isfinite(contour.points[p].y))
            return invalid(describeContour(contours, f, s, slice.z, c) + ", point " + std::to_string(p) +
                           ": non-finite coordinate");
          if (std::abs(contour.points[p].x) > kMaxCoordinate || std::abs(contour.points[p].y) > kMaxCoordinate)
            return invalid(describeContour(contours, f, s, slice.z, c) + ", point " + std::to_string(p) + ": (" +
                           formatNumber(contour.points[p].x) + ", " + formatNumber(contour.points[p].y) + ") is beyond " +
                           formatNumber(kMaxCoordinate) + " units from the origin");
        }
        dropRepeatedPoints(contour);
        if (contour.points.size() < 3 || countDistinct(contour) < 3)
          return invalid(describeContour(contours, f, s, slice.z, c) + ": fewer than 3 distinct points");
      }
    }
  }

  contours.planeTolerance = planeToleranceOf(contours);
  snapToSharedPlanes(contours);
  for (int f = 0; f < featureCount; ++f) {
    mergeSlicesOfOnePlane(contours.features[static_cast<std::size_t>(f)]);
    Feature& feature = contours.features[static_cast<std::size_t>(f)];
    for (int s = 0; s < static_cast<int>(feature.slices.size()); ++s) {
      dropRepeatedContours(contours, f, feature.slices[static_cast<std::size_t>(s)], s);
      warnAboutSelfCrossings(contours, f, feature.slices[static_cast<std::size_t>(s)], s);
    }
  }

  if (!contours.order.empty()) {
    std::vector<int> seen(featureCount, 0);
    for (std::size_t i = 0; i < contours.order.size(); ++i) {
      const int f = contours.order[i];
      if (f < 0 || f >= featureCount)
        return invalid(source + ": order entry " + std::to_string(i) + " (" + std::to_string(f) + ") is not a feature index");
      if (seen[f]++) return invalid(describeFeature(contours, f) + ": named more than once in order");
    }
    for (int f = 0; f < featureCount; ++f)
      if (!seen[f]) return invalid(describeFeature(contours, f) + ": missing from order");
  }
  return {};
}

}  // namespace scansurf
