// scansurf: objects of closed planar contours (Reconstruct traces, IMOD contours) into features.
#include "io/object_features.h"

#include <fnmatch.h>

#include <algorithm>
#include <map>
#include <set>

#include "geometry/contours/polygon.h"
#include "geometry/contours/validate.h"

namespace scansurf {

namespace {

std::size_t distinctPoints(std::vector<Point2> pts) {
  auto less = [](Point2 a, Point2 b) { return a.x != b.x ? a.x < b.x : a.y < b.y; };
  std::sort(pts.begin(), pts.end(), less);
  return static_cast<std::size_t>(
      std::unique(pts.begin(), pts.end(), [](Point2 a, Point2 b) { return a.x == b.x && a.y == b.y; }) - pts.begin());
}

std::string quotedNames(const std::vector<RawObject>& objects) {
  std::string names;
  for (const RawObject& o : objects) names += (names.empty() ? "\"" : ", \"") + o.info.name + "\"";
  return names.empty() ? std::string("none") : names;
}

}  // namespace

bool objectNameMatches(const std::string& pattern, const std::string& name) {
  return fnmatch(pattern.c_str(), name.c_str(), FNM_CASEFOLD) == 0;
}

bool objectSelected(const std::vector<std::string>& patterns, const std::string& name) {
  return patterns.empty() ||
         std::any_of(patterns.begin(), patterns.end(), [&](const std::string& p) { return objectNameMatches(p, name); });
}

void makeObjectNamesUnique(std::vector<RawObject>& objects, const std::string& file, std::vector<std::string>& warnings) {
  std::set<std::string> usedNames;
  for (RawObject& o : objects) {
    if (usedNames.insert(o.info.name).second) continue;
    std::string renamed = o.info.name + " #" + std::to_string(o.info.number);
    while (!usedNames.insert(renamed).second) renamed += "'";
    warnings.push_back(file + ": object \"" + o.info.name + "\" (#" + std::to_string(o.info.number) +
                       "): name used by another object; the feature is called \"" + renamed + "\"");
    o.info.name = renamed;
  }
}

Result<std::vector<ObjectInfo>> buildObjectFeatures(std::vector<RawObject>& objects, const ObjectFeatureOptions& options,
                                                    ContourSet& out) {
  const std::string& file = out.source;
  makeObjectNamesUnique(objects, file, out.warnings);
  for (const std::string& pattern : options.patterns) {
    const bool any =
        std::any_of(objects.begin(), objects.end(), [&](const RawObject& o) { return objectNameMatches(pattern, o.info.name); });
    if (!any)
      return makeError(Errc::InvalidArgument, file + ": the object pattern \"" + pattern +
                                                  "\" matches no object; the file holds " + quotedNames(objects));
  }

  if (!options.patterns.empty()) out.fileExtent = closedContoursExtent(objects);  // the default grid's lattice
  std::vector<ObjectInfo> infos;
  for (RawObject& o : objects) {
    ObjectInfo& info = o.info;
    info.selected = objectSelected(options.patterns, info.name);
    int degenerate = 0;
    Feature feature;
    feature.name = info.name;
    feature.color = info.color;
    std::map<double, std::size_t> sliceOfZ;
    for (ObjectContour& c : o.closed) {
      if (distinctPoints(c.points) < 3) {
        ++degenerate;
        continue;
      }
      ++info.contours;
      auto [it, inserted] = sliceOfZ.emplace(c.z, feature.slices.size());
      if (inserted) feature.slices.push_back(FeatureSlice{c.z, {}});
      feature.slices[it->second].contours.push_back(Contour{std::move(c.points)});
    }
    info.skipped += degenerate;
    if (degenerate > 0)
      out.warnings.push_back(file + ": object \"" + info.name + "\": skipped " + std::to_string(degenerate) +
                             " closed contour(s) with fewer than 3 distinct points");
    info.slices = static_cast<int>(sliceOfZ.size());
    if (!sliceOfZ.empty()) info.zMin = sliceOfZ.begin()->first, info.zMax = sliceOfZ.rbegin()->first;
    if (info.selected && !feature.slices.empty()) {
      info.feature = static_cast<int>(out.features.size());
      out.features.push_back(std::move(feature));
    }
    infos.push_back(info);
  }

  if (out.features.empty()) {
    if (!options.requireFeatures) return infos;
    if (objects.empty()) return makeError(Errc::InvalidInput, file + ": no objects");
    return makeError(Errc::InvalidInput, file + (options.patterns.empty() ? ": no object has closed contours"
                                                                          : ": no selected object has closed contours"));
  }
  SCANSURF_TRY(validateAndNormalize(out));
  return infos;
}

}  // namespace scansurf
