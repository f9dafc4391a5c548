// scansurf: DICOM RT Structure Set input (DICOM PS3.3 C.8.8.5 Structure Set, C.8.8.6 ROI
// Contour, C.8.8.8 RT ROI Observations), read with DCMTK's dcmdata. Linear in the file's size:
// sequences are walked item after item (never indexed, which costs a walk from the start each
// time), ROIs are found by number in a hash map, and Contour Data is parsed once from its text.
#include "io/rtstruct_reader.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcdict.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcitem.h>
#include <dcmtk/dcmdata/dcsequen.h>
#include <dcmtk/dcmdata/dcuid.h>
#include <fnmatch.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <unordered_map>

#include "geometry/contours/polygon.h"
#include "geometry/contours/validate.h"
#include "io/dicom_common.h"

namespace scansurf {

namespace {

Unexpected invalid(std::string message) { return makeError(Errc::InvalidInput, std::move(message)); }

std::string str(const OFString& s) { return std::string(s.c_str()); }

// One CLOSED_PLANAR contour as read: its plane and its in-plane points.
struct RawContour {
  double z = 0;
  std::vector<Point2> points;
};

struct RawRoi {
  RoiInfo info;
  std::vector<RawContour> closed;
  bool hasContourItem = false;
};

std::string describeRoi(const std::string& file, const RoiInfo& roi) {
  return file + ": ROI \"" + roi.name + "\" (#" + std::to_string(roi.number) + ")";
}

// Newell's method: the normal of the best-fit plane of a closed polygon (not normalized).
std::array<double, 3> newellNormal(const std::vector<double>& xyz) {
  std::array<double, 3> n{0, 0, 0};
  const std::size_t count = xyz.size() / 3;
  for (std::size_t i = 0; i < count; ++i) {
    const double* a = &xyz[3 * i];
    const double* b = &xyz[3 * ((i + 1) % count)];
    n[0] += (a[1] - b[1]) * (a[2] + b[2]);
    n[1] += (a[2] - b[2]) * (a[0] + b[0]);
    n[2] += (a[0] - b[0]) * (a[1] + b[1]);
  }
  return n;
}

// Explains why a contour whose points span more than the tolerance in z is rejected.
std::string notAxialReason(const std::vector<double>& xyz, double zMin, double zMax, double tol) {
  std::string why = "its points span z " + formatNumber(zMin) + " .. " + formatNumber(zMax) + " mm (more than the " +
                    formatNumber(tol) + " mm tolerance)";
  auto n = newellNormal(xyz);
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  bool planar = len > 0;
  if (planar) {
    for (double& c : n) c /= len;
    const double d = n[0] * xyz[0] + n[1] * xyz[1] + n[2] * xyz[2];
    for (std::size_t i = 0; i < xyz.size(); i += 3)
      if (std::abs(n[0] * xyz[i] + n[1] * xyz[i + 1] + n[2] * xyz[i + 2] - d) > tol) planar = false;
  }
  if (!planar) return "it is not planar: " + why;
  auto round3 = [](double v) { return formatNumber(std::round(v * 1000) / 1000 + 0.0); };
  return "it is not axial: it lies in the plane with normal (" + round3(n[0]) + ", " + round3(n[1]) + ", " + round3(n[2]) +
         "), " + why + "; only axial contours (constant z) are supported";
}

std::size_t distinctPoints(std::vector<Point2> pts) {
  auto less = [](Point2 a, Point2 b) { return a.x != b.x ? a.x < b.x : a.y < b.y; };
  std::sort(pts.begin(), pts.end(), less);
  return static_cast<std::size_t>(
      std::unique(pts.begin(), pts.end(), [](Point2 a, Point2 b) { return a.x == b.x && a.y == b.y; }) - pts.begin());
}

// The items of parent's sequence `tag`, in order (none when it is absent), found in one walk.
std::vector<DcmItem*> itemsOf(DcmItem& parent, const DcmTagKey& tag) {
  std::vector<DcmItem*> items;
  DcmSequenceOfItems* sequence = nullptr;
  if (parent.findAndGetSequence(tag, sequence).bad() || !sequence) return items;
  items.reserve(sequence->card());
  for (DcmObject* o = sequence->nextInContainer(nullptr); o; o = sequence->nextInContainer(o))
    items.push_back(static_cast<DcmItem*>(o));
  return items;
}

std::string stringOf(DcmItem& item, const DcmTagKey& tag) {
  OFString value;
  item.findAndGetOFString(tag, value);
  return str(value);
}

// The whole value of a multi-valued string element (values joined by backslashes), empty when absent.
std::string_view rawValue(DcmItem& item, const DcmTagKey& tag) {
  const char* text = nullptr;
  if (item.findAndGetString(tag, text).bad() || !text) return {};
  return text;
}

// Decimal String values (PS3.5 6.2: backslash-separated, optional spaces and leading '+'), parsed
// once, in order. Nullopt when one is not a number.
std::optional<std::vector<double>> parseDecimalStrings(std::string_view text) {
  std::vector<double> values;
  values.reserve(text.size() / 8 + 1);
  while (true) {
    const std::size_t end = std::min(text.find('\\'), text.size());
    std::string_view v = text.substr(0, end);
    while (!v.empty() && (v.front() == ' ' || v.front() == '\0')) v.remove_prefix(1);
    while (!v.empty() && (v.back() == ' ' || v.back() == '\0')) v.remove_suffix(1);
    if (!v.empty() && v.front() == '+') v.remove_prefix(1);
    double value = 0;
    const auto [ptr, ec] = std::from_chars(v.data(), v.data() + v.size(), value);
    if (v.empty() || ec != std::errc() || ptr != v.data() + v.size()) return std::nullopt;
    values.push_back(value);
    if (end == text.size()) return values;
    text.remove_prefix(end + 1);
  }
}

// ROI Display Color (3006,002A), when it holds three values 0..255.
std::optional<Rgb> displayColor(DcmItem& item) {
  Sint32 rgb[3];
  Rgb color;
  for (unsigned long c = 0; c < 3; ++c) {
    if (item.findAndGetSint32(DCM_ROIDisplayColor, rgb[c], c).bad() || rgb[c] < 0 || rgb[c] > 255) return std::nullopt;
    color[c] = static_cast<std::uint8_t>(rgb[c]);
  }
  return color;
}

// One Contour Sequence item: its points checked (triplets, finite) and, when CLOSED_PLANAR
// and axial, added to roi.closed.
Result<void> readContourItem(const std::string& where, DcmItem& contour, RawRoi& roi, bool& anyPoint,
                             const RtStructOptions& options) {
  const std::string type = stringOf(contour, DCM_ContourGeometricType);
  if (type.empty()) return invalid(where + ": missing Contour Geometric Type (3006,0042)");
  ++roi.info.contoursByType[type];
  const std::string_view text = rawValue(contour, DCM_ContourData);
  if (text.empty()) return invalid(where + ": missing Contour Data (3006,0050)");
  const std::optional<std::vector<double>> parsed = parseDecimalStrings(text);
  if (!parsed) return invalid(where + ": Contour Data (3006,0050) is not a list of numbers");
  const std::vector<double>& data = *parsed;
  if (data.size() % 3 != 0)
    return invalid(where + ": Contour Data (3006,0050) holds " + std::to_string(data.size()) +
                   " values, not a multiple of 3 (x, y, z triplets)");
  for (std::size_t v = 0; v < data.size(); ++v)
    if (!std::isfinite(data[v]))
      return invalid(where + ", point " + std::to_string(v / 3) + ": non-finite coordinate in Contour Data (3006,0050)");
  double zMin = data[2], zMax = data[2];
  for (std::size_t v = 2; v < data.size(); v += 3) zMin = std::min(zMin, data[v]), zMax = std::max(zMax, data[v]);
  if (!anyPoint) roi.info.zMin = zMin, roi.info.zMax = zMax;
  roi.info.zMin = std::min(roi.info.zMin, zMin);
  roi.info.zMax = std::max(roi.info.zMax, zMax);
  anyPoint = true;
  if (type != "CLOSED_PLANAR") return {};
  if (zMax - zMin > options.sliceTolerance)
    return invalid(where + ": " + notAxialReason(data, zMin, zMax, options.sliceTolerance));
  RawContour raw;
  raw.z = data[2];
  raw.points.reserve(data.size() / 3);
  for (std::size_t v = 0; v < data.size(); v += 3) raw.points.push_back({data[v], data[v + 1]});
  roi.closed.push_back(std::move(raw));
  return {};
}

// Reads the ROI Contour Sequence item of one ROI into `roi`.
Result<void> readRoiContours(const std::string& file, DcmItem& item, RawRoi& roi, const RtStructOptions& options) {
  roi.hasContourItem = true;
  if (const auto color = displayColor(item)) roi.info.color = *color;
  bool anyPoint = false;
  std::size_t index = 0;
  for (DcmItem* contour : itemsOf(item, DCM_ContourSequence)) {
    const std::string where = describeRoi(file, roi.info) + ", contour item " + std::to_string(++index);
    SCANSURF_TRY(readContourItem(where, *contour, roi, anyPoint, options));
  }
  return {};
}

// Rejects an object that is not an RT Structure Set, naming what it is, or that lacks the
// sequences surfacing needs.
Result<void> checkIsRtStruct(const std::string& file, DcmDataset& dataset) {
  OFString sopClass, modality;
  dataset.findAndGetOFString(DCM_SOPClassUID, sopClass);
  dataset.findAndGetOFString(DCM_Modality, modality);
  if (sopClass != UID_RTStructureSetStorage && modality != "RTSTRUCT") {
    std::string what = modality.empty() ? std::string("a DICOM object") : "a DICOM " + str(modality) + " object";
    if (!sopClass.empty()) {
      const char* name = dcmFindNameOfUID(sopClass.c_str());
      what += " (SOP class " + (name ? std::string(name) : str(sopClass)) + ")";
    }
    return invalid(file + ": " + what + ", not an RT Structure Set (RTSTRUCT)");
  }
  for (const auto& [tag, name] : {std::pair{DCM_StructureSetROISequence, "Structure Set ROI Sequence (3006,0020)"},
                                  std::pair{DCM_ROIContourSequence, "ROI Contour Sequence (3006,0039)"}}) {
    if (!dataset.tagExists(tag)) return invalid(file + ": missing required " + std::string(name));
  }
  return {};
}

// The structure set's label, its frame of reference and the image series it refers to.
void readStructureSetHeader(DcmDataset& dataset, RtStructure& out) {
  out.label = stringOf(dataset, DCM_StructureSetLabel);
  for (DcmItem* frame : itemsOf(dataset, DCM_ReferencedFrameOfReferenceSequence)) {
    if (out.frameOfReferenceUid.empty()) out.frameOfReferenceUid = stringOf(*frame, DCM_FrameOfReferenceUID);
    for (DcmItem* study : itemsOf(*frame, DCM_RTReferencedStudySequence))
      for (DcmItem* series : itemsOf(*study, DCM_RTReferencedSeriesSequence))
        if (std::string uid = stringOf(*series, DCM_SeriesInstanceUID); !uid.empty())
          out.referencedSeriesUids.push_back(std::move(uid));
  }
}

using RoiIndex = std::unordered_map<Sint32, std::size_t>;  // ROI Number -> position in the ROI list

// Structure Set ROI Sequence: numbers and names, in file order; a number used twice is an error.
Result<std::vector<RawRoi>> readRoiDefinitions(const std::string& file, DcmDataset& dataset, RoiIndex& byNumber) {
  std::vector<RawRoi> rois;
  std::size_t index = 0;
  for (DcmItem* item : itemsOf(dataset, DCM_StructureSetROISequence)) {
    ++index;
    RawRoi roi;
    Sint32 number = 0;
    if (item->findAndGetSint32(DCM_ROINumber, number).bad())
      return invalid(file + ": Structure Set ROI Sequence item " + std::to_string(index) + ": missing ROI Number (3006,0022)");
    roi.info.number = number;
    roi.info.name = stringOf(*item, DCM_ROIName);
    if (roi.info.name.empty()) roi.info.name = "ROI-" + std::to_string(number);
    const auto [at, added] = byNumber.emplace(number, rois.size());
    if (!added)
      return invalid(file + ": ROI Number " + std::to_string(number) + " is used twice (\"" + rois[at->second].info.name +
                     "\" and \"" + roi.info.name + "\")");
    rois.push_back(std::move(roi));
  }
  return rois;
}

RawRoi* findRoi(std::vector<RawRoi>& rois, const RoiIndex& byNumber, Sint32 number) {
  const auto at = byNumber.find(number);
  return at == byNumber.end() ? nullptr : &rois[at->second];
}

// RT ROI Observations Sequence: each ROI's interpreted type (EXTERNAL, ORGAN, ...).
void readInterpretedTypes(DcmDataset& dataset, const RoiIndex& byNumber, std::vector<RawRoi>& rois) {
  for (DcmItem* item : itemsOf(dataset, DCM_RTROIObservationsSequence)) {
    Sint32 number = 0;
    if (item->findAndGetSint32(DCM_ReferencedROINumber, number).bad()) continue;
    if (RawRoi* roi = findRoi(rois, byNumber, number)) roi->info.interpretedType = stringOf(*item, DCM_RTROIInterpretedType);
  }
}

// Keeps only the ROIs whose name matches one of `patterns` selected (all of them when there
// are none). A pattern that matches no ROI is an error that lists the names there are.
Result<void> selectRois(const std::string& file, const std::vector<std::string>& patterns, std::vector<RawRoi>& rois) {
  for (const std::string& pattern : patterns) {
    bool any = false;
    for (const RawRoi& r : rois) any = any || roiNameMatches(pattern, r.info.name);
    if (!any) {
      std::string names;
      for (const RawRoi& r : rois) names += (names.empty() ? "" : ", ") + ("\"" + r.info.name + "\"");
      return makeError(Errc::InvalidArgument, file + ": the ROI pattern \"" + pattern + "\" matches no ROI; the file holds " +
                                                  (names.empty() ? std::string("none") : names));
    }
  }
  for (RawRoi& r : rois) {
    if (patterns.empty()) continue;
    r.info.selected =
        std::any_of(patterns.begin(), patterns.end(), [&](const std::string& p) { return roiNameMatches(p, r.info.name); });
  }
  return {};
}

// ROI Contour Sequence: the contours of each ROI. An item for an undefined ROI is skipped
// with a warning.
Result<void> readAllRoiContours(const std::string& file, DcmDataset& dataset, const RtStructOptions& options,
                                const RoiIndex& byNumber, std::vector<RawRoi>& rois, std::vector<std::string>& warnings) {
  std::size_t index = 0;
  for (DcmItem* item : itemsOf(dataset, DCM_ROIContourSequence)) {
    ++index;
    Sint32 number = 0;
    if (item->findAndGetSint32(DCM_ReferencedROINumber, number).bad())
      return invalid(file + ": ROI Contour Sequence item " + std::to_string(index) +
                     ": missing Referenced ROI Number (3006,0084)");
    RawRoi* roi = findRoi(rois, byNumber, number);
    if (!roi) {
      warnings.push_back(file + ": ROI Contour Sequence item " + std::to_string(index) + " refers to ROI number " +
                         std::to_string(number) + ", which the Structure Set ROI Sequence does not define; skipped");
      continue;
    }
    SCANSURF_TRY(readRoiContours(file, *item, *roi, options));
  }
  return {};
}

// Slice planes shared by every selected ROI, so abutting structures meet on one plane: the
// plane of each closed contour of the selected ROIs, in ROI order.
std::vector<double> sharedSlicePlanes(const std::vector<RawRoi>& rois, double tolerance) {
  std::vector<double> allZ;
  for (const RawRoi& r : rois)
    if (r.info.selected)
      for (const RawContour& c : r.closed) allZ.push_back(c.z);
  return groupSlicePlanes(allZ, tolerance);
}

// Where each ROI's planes start in sharedSlicePlanes's result.
std::vector<std::size_t> sharedPlaneStarts(const std::vector<RawRoi>& rois) {
  std::vector<std::size_t> planeStart(rois.size(), 0);
  for (std::size_t i = 0, next = 0; i < rois.size(); ++i) {
    planeStart[i] = next;
    if (rois[i].info.selected) next += rois[i].closed.size();
  }
  return planeStart;
}

// Features in ROI order, except that EXTERNAL ROIs (the body outline) come last: where a
// drawn organ pokes out of BODY on some slice, nesting cannot prove BODY contains it, and
// among siblings the earlier feature wins, so the organ keeps its voxels.
std::vector<std::size_t> featureOrder(const std::vector<RawRoi>& rois) {
  std::vector<std::size_t> roiOrder(rois.size());
  for (std::size_t i = 0; i < rois.size(); ++i) roiOrder[i] = i;
  std::stable_partition(roiOrder.begin(), roiOrder.end(),
                        [&](std::size_t i) { return rois[i].info.interpretedType != "EXTERNAL"; });
  return roiOrder;
}

// The slice count of an unselected ROI, for listing: its own planes, not the shared ones.
int ownSliceCount(const RawRoi& r, double tolerance) {
  std::vector<double> zs;
  for (const RawContour& c : r.closed) zs.push_back(c.z);
  const auto planes = groupSlicePlanes(zs, tolerance);
  return static_cast<int>(std::set<double>(planes.begin(), planes.end()).size());
}

// Warns once for all of an ROI's contours that are not CLOSED_PLANAR (points, open curves).
void warnSkippedContourTypes(const std::string& who, const RoiInfo& info, std::vector<std::string>& warnings) {
  int skippedOther = 0;
  std::string otherTypes;
  for (const auto& [type, count] : info.contoursByType)
    if (type != "CLOSED_PLANAR") skippedOther += count, otherTypes += (otherTypes.empty() ? "" : ", ") + type;
  if (skippedOther > 0)
    warnings.push_back(who + ": skipped " + std::to_string(skippedOther) + " " + otherTypes +
                       " contour(s); only CLOSED_PLANAR contours are surfaced");
}

// The ROI's name, or "name #number" when another ROI's feature has it already; never the name
// another ROI of the file has (reserved): "A", "A #3", "A" gives "A", "A #3", "A #3 (2)".
std::string uniqueFeatureName(const std::string& who, const RoiInfo& info, std::set<std::string>& usedNames,
                              const std::set<std::string>& reserved, std::vector<std::string>& warnings) {
  if (usedNames.insert(info.name).second) return info.name;
  const std::string base = info.name + " #" + std::to_string(info.number);
  std::string name = base;
  for (int k = 2; usedNames.count(name) || reserved.count(name); ++k) name = base + " (" + std::to_string(k) + ")";
  usedNames.insert(name);
  warnings.push_back(who + ": name used by another ROI; the feature is called \"" + name + "\"");
  return name;
}

// Moves the closed contours into feature's slices, contour i on plane planes[i]; returns how
// many were skipped for having fewer than 3 distinct points.
int addSlices(std::vector<RawContour>& closed, std::span<const double> planes, Feature& feature) {
  int degenerate = 0;
  std::size_t zIndex = 0;
  std::map<double, std::size_t> sliceOfPlane;
  for (RawContour& c : closed) {
    const double z = planes[zIndex++];
    if (distinctPoints(c.points) < 3) {
      ++degenerate;
      continue;
    }
    auto [it, inserted] = sliceOfPlane.emplace(z, feature.slices.size());
    if (inserted) feature.slices.push_back(FeatureSlice{z, {}});
    feature.slices[it->second].contours.push_back(Contour{std::move(c.points)});
  }
  return degenerate;
}

// Appends selected ROI r as a feature of out.contours, if any of its contours is usable, and
// records its slice count and feature index; warns about what it skipped.
void addFeature(const std::string& file, RawRoi& r, std::span<const double> planes, std::set<std::string>& usedNames,
                const std::set<std::string>& reserved, RtStructure& out) {
  const std::string who = describeRoi(file, r.info);
  warnSkippedContourTypes(who, r.info, out.warnings);
  if (!r.hasContourItem || r.info.contoursByType.empty()) {
    out.warnings.push_back(who + ": no contours (empty ROI)");
    return;
  }
  Feature feature;
  feature.name = uniqueFeatureName(who, r.info, usedNames, reserved, out.warnings);
  feature.color = r.info.color;
  feature.sourceNumber = r.info.number;
  feature.interpretedType = r.info.interpretedType;
  const int degenerate = addSlices(r.closed, planes, feature);
  if (degenerate > 0)
    out.warnings.push_back(who + ": skipped " + std::to_string(degenerate) +
                           " CLOSED_PLANAR contour(s) with fewer than 3 distinct points");
  r.info.slices = static_cast<int>(feature.slices.size());
  if (feature.slices.empty()) return;
  r.info.feature = static_cast<int>(out.contours.features.size());
  out.contours.features.push_back(std::move(feature));
}

// The features of the selected ROIs, on shared slice planes, into out.contours.
void addFeatures(const std::string& file, double sliceTolerance, std::vector<RawRoi>& rois, RtStructure& out) {
  const std::vector<double> planeOf = sharedSlicePlanes(rois, sliceTolerance);
  const std::vector<std::size_t> planeStart = sharedPlaneStarts(rois);
  std::set<std::string> usedNames, reserved;
  for (const RawRoi& r : rois)
    if (r.info.selected) reserved.insert(r.info.name);
  for (std::size_t roiIndex : featureOrder(rois)) {
    RawRoi& r = rois[roiIndex];
    if (!r.info.selected) {
      r.info.slices = ownSliceCount(r, sliceTolerance);
      continue;
    }
    const std::span<const double> planes(planeOf.data() + planeStart[roiIndex], r.closed.size());
    addFeature(file, r, planes, usedNames, reserved, out);
  }
}

}  // namespace

bool hasDicomPreamble(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  char buffer[132];
  if (!in.read(buffer, sizeof buffer)) return false;
  return std::string_view(buffer + 128, 4) == "DICM";
}

bool roiNameMatches(const std::string& pattern, const std::string& name) {
  return fnmatch(pattern.c_str(), name.c_str(), FNM_CASEFOLD) == 0;
}

std::vector<double> groupSlicePlanes(const std::vector<double>& z, double tolerance) {
  std::vector<std::size_t> order(z.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return z[a] < z[b]; });
  std::vector<double> plane(z.size());
  std::size_t begin = 0;
  while (begin < order.size()) {
    std::size_t end = begin + 1;
    while (end < order.size() && z[order[end]] - z[order[begin]] <= tolerance) ++end;
    // The most frequent value of the group (sorted, so equal values are adjacent); among
    // equally frequent ones the shortest in decimal (12.5 over 12.4999), then the lowest.
    double best = z[order[begin]];
    std::size_t bestCount = 0;
    for (std::size_t i = begin; i < end;) {
      std::size_t j = i;
      while (j < end && z[order[j]] == z[order[i]]) ++j;
      const double v = z[order[i]];
      if (j - i > bestCount || (j - i == bestCount && formatNumber(v).size() < formatNumber(best).size()))
        best = v, bestCount = j - i;
      i = j;
    }
    for (std::size_t i = begin; i < end; ++i) plane[order[i]] = best;
    begin = end;
  }
  return plane;
}

Result<RtStructure> readRtStruct(const std::filesystem::path& path, const RtStructOptions& options) {
  const std::string file = path.string();
  if (!(options.sliceTolerance >= 0) || !std::isfinite(options.sliceTolerance))
    return makeError(Errc::InvalidArgument, "slice tolerance must be finite and not negative");
  SCANSURF_ASSIGN_OR_RETURN(DicomFile dicom, loadDicomFile(path));
  DcmDataset& dataset = dicom.dataset();
  SCANSURF_TRY(checkIsRtStruct(file, dataset));

  RtStructure out;
  out.contours.source = file;
  out.contours.units = "mm";
  decodeTextToUtf8(file, dataset, out.warnings);
  readStructureSetHeader(dataset, out);
  RoiIndex byNumber;
  SCANSURF_ASSIGN_OR_RETURN(std::vector<RawRoi> rois, readRoiDefinitions(file, dataset, byNumber));
  readInterpretedTypes(dataset, byNumber, rois);
  SCANSURF_TRY(selectRois(file, options.roiPatterns, rois));
  SCANSURF_TRY(readAllRoiContours(file, dataset, options, byNumber, rois, out.warnings));
  if (!options.roiPatterns.empty()) out.contours.fileExtent = closedContoursExtent(rois);
  addFeatures(file, options.sliceTolerance, rois, out);
  for (RawRoi& r : rois) out.rois.push_back(std::move(r.info));

  if (out.contours.features.empty()) {
    if (!options.requireFeatures) return out;
    return invalid(file + (options.roiPatterns.empty() ? ": no ROI has CLOSED_PLANAR contours"
                                                       : ": no selected ROI has CLOSED_PLANAR contours"));
  }
  SCANSURF_TRY(validateAndNormalize(out.contours));
  return out;
}

}  // namespace scansurf
