// scansurf: what the Reconstruct and IMOD readers share: named objects of closed planar
// contours, selected by name patterns and turned into validated features.
#pragma once

#include <string>
#include <vector>

#include "scansurf/contours.h"
#include "scansurf/input.h"
#include "scansurf/result.h"

namespace scansurf {

// One closed contour of an object as read: its plane and its in-plane points.
struct ObjectContour {
  double z = 0;
  std::vector<Point2> points;
};

struct RawObject {
  // number, name and color set by the reader; skipped counts what the reader left out (it
  // words the warning itself). The rest is filled in by buildObjectFeatures.
  ObjectInfo info;
  std::vector<ObjectContour> closed;
};

struct ObjectFeatureOptions {
  std::vector<std::string> patterns;  // glob, case-insensitive; empty = every object
  bool requireFeatures = true;        // false: nothing to surface is not an error (listing)
};

// Case-insensitive glob match (*, ?, [...]) of a whole name.
bool objectNameMatches(const std::string& pattern, const std::string& name);

// Whether any pattern matches the name; true when there are none.
bool objectSelected(const std::vector<std::string>& patterns, const std::string& name);

// Renames the second and later objects of a repeated name to "name #N" (N the object's
// number), each with a warning naming `file`.
void makeObjectNamesUnique(std::vector<RawObject>& objects, const std::string& file, std::vector<std::string>& warnings);

// Makes repeated names unique (makeObjectNamesUnique), applies the patterns, skips closed contours of fewer than 3 distinct
// points (one warning per object), and appends one feature per selected object with contours to out.features, its slices grouped
// by exact z, in the order of `objects`. Fills each info's contours, slices, z range, selected and feature. Then validates `out`
// (validateAndNormalize) when it has features. out.source names the file in messages; warnings go to out.warnings. Errors:
// Errc::InvalidArgument for a pattern that matches no object (the message lists the objects); Errc::InvalidInput when no
// (selected) object has closed contours and options.requireFeatures, or what validateAndNormalize finds.
Result<std::vector<ObjectInfo>> buildObjectFeatures(std::vector<RawObject>& objects, const ObjectFeatureOptions& options,
                                                    ContourSet& out);

}  // namespace scansurf
