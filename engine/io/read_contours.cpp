// scansurf: readContours, listRois and listObjects, the public entry to every contour reader.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/guard.h"
#include "core/memory.h"
#include "geometry/contours/polygon.h"
#include "geometry/contours/validate.h"
#include "io/contours_json.h"
#include "io/ct_series.h"
#include "io/dicom_common.h"
#include "io/imod_reader.h"
#include "io/reconstruct_reader.h"
#include "io/rtstruct_reader.h"
#include "io/slicer_reader.h"
#include "scansurf/input.h"

namespace scansurf {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// The frame of reference and referenced series must agree before the CT's lattice is used.
Result<void> checkReference(const RtStructure& rt, const CtSeries& ct, const std::string& path, const std::string& ctDir,
                            std::vector<std::string>& warnings) {
  if (!rt.frameOfReferenceUid.empty() && !ct.frameOfReferenceUid.empty() && rt.frameOfReferenceUid != ct.frameOfReferenceUid)
    return makeError(Errc::InvalidInput, path + ": frame of reference " + rt.frameOfReferenceUid +
                                             " differs from the reference series' (" + ct.frameOfReferenceUid + " in " + ctDir +
                                             "): the coordinates are not comparable");
  const auto& series = rt.referencedSeriesUids;
  if (!series.empty() && std::find(series.begin(), series.end(), ct.seriesUid) == series.end())
    warnings.push_back(path + ": the contours reference series " + series.front() + ", not " + ct.seriesUid + " (" + ctDir +
                       "); using it as the reference grid anyway");
  return {};
}

std::string describeReference(const CtSeries& ct, const std::string& ctDir) {
  const std::string line = std::to_string(ct.columns) + " x " + std::to_string(ct.rows) + " pixels of " +
                           formatNumber(ct.spacingX) + " x " + formatNumber(ct.spacingY) + " mm, " +
                           std::to_string(ct.sliceZ.size()) + " slices z " + formatNumber(ct.sliceZ.front()) + " .. " +
                           formatNumber(ct.sliceZ.back());
  return "reference " + (ct.modality.empty() ? std::string("series") : ct.modality) + " " + ctDir + ": " + line +
         "; CT voxel (i, j, k) is grid voxel (i+1, j+1, k+1) unless the contours reach beyond the CT (the grid then "
         "grows by whole CT pixels)";
}

Result<ContourSet> readStructureSet(const std::filesystem::path& path, const ReadOptions& options) {
  RtStructOptions rtOptions;
  rtOptions.roiPatterns = options.roiPatterns;
  SCANSURF_ASSIGN_OR_RETURN(RtStructure rt, readRtStruct(path, rtOptions));
  ContourSet contours = std::move(rt.contours);
  contours.warnings = std::move(rt.warnings);
  contours.frameOfReferenceUid = rt.frameOfReferenceUid;
  int surfaced = 0;
  for (const RoiInfo& roi : rt.rois) surfaced += roi.feature >= 0;
  contours.notes.push_back("RTSTRUCT \"" + rt.label + "\": " + std::to_string(rt.rois.size()) + " ROIs, " +
                           std::to_string(surfaced) + " with closed contours surfaced (patient LPS coordinates, mm)");
  if (options.referenceSeries.empty()) return contours;
  const std::string ctDir = options.referenceSeries.string();
  SCANSURF_ASSIGN_OR_RETURN(const CtSeries ct, readCtSeries(options.referenceSeries));
  SCANSURF_TRY(checkReference(rt, ct, path.string(), ctDir, contours.warnings));
  SCANSURF_ASSIGN_OR_RETURN(const std::vector<double> off, placeOnCtSlices(contours, ct, rtOptions.sliceTolerance));
  contours.reference = gridReferenceOf(ct);
  if (!off.empty()) {  // a partial series: its lattice in-plane, the contours' own planes in z
    std::vector<double>& zs = contours.reference->sliceZ;
    zs.insert(zs.end(), off.begin(), off.end());
    std::sort(zs.begin(), zs.end());
    contours.warnings.push_back(path.string() + ": the reference series " + ctDir + " has no slice at " +
                                std::to_string(off.size()) + " contour plane(s) (z=" + formatNumber(off.front()) +
                                (off.size() > 1 ? " to " + formatNumber(off.back()) : std::string()) +
                                "): its pixel lattice places the surfaces in-plane, the contours their planes; a DICOM "
                                "SEG holds only the series' own slices");
  }
  contours.notes.push_back(describeReference(ct, ctDir));
  // The report's input files: the structure set first (withFiles), then every CT file read.
  contours.files.push_back(path.string());
  contours.files.insert(contours.files.end(), ct.files.begin(), ct.files.end());
  return contours;
}

constexpr const char* kSupportedFormats =
    "scansurf contour-set JSON; DICOM RT Structure Set (with or without the Part 10 header); Reconstruct series "
    "(XML .ser or section file NAME.<number>); IMOD binary model (.mod); 3D Slicer planar-contour segmentation "
    "(.seg.vtm or a segment's .vtp)";

// The first bytes of a file, printable, for messages.
std::string describeStart(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  char buffer[16];
  in.read(buffer, sizeof buffer);
  const auto n = static_cast<std::size_t>(in.gcount());
  if (n == 0) return "it is empty";
  std::string text;
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<unsigned char>(buffer[i]);
    if (c >= 0x20 && c < 0x7f && c != '\\' && c != '"') {
      text += static_cast<char>(c);
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", c);
      text += hex;
    }
  }
  return "it starts with \"" + text + "\"";
}

// Why a file of an unrecognised format cannot be read: Errc::Io when it cannot be opened.
Unexpected unrecognised(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::error_code ec;
  if (!in || std::filesystem::is_directory(path, ec)) return makeError(Errc::Io, path.string() + ": cannot open the file");
  return makeError(Errc::InvalidInput, path.string() + ": not a contour file scansurf reads (" + describeStart(path) +
                                           "); supported formats, recognised by content: " + kSupportedFormats);
}

// --roi, --reference and --object each apply to some formats only.
Result<void> checkOptionsApply(InputFormat format, const std::filesystem::path& path, const ReadOptions& options) {
  const bool dicom = format == InputFormat::RtStruct;
  const bool objects = format == InputFormat::ReconstructSeries || format == InputFormat::ImodModel;
  const bool segments = format == InputFormat::SlicerSegmentation;
  if (!dicom && !segments && !options.roiPatterns.empty())
    return makeError(Errc::InvalidArgument,
                     std::string("ROI selection applies to DICOM RTSTRUCT and 3D Slicer segmentation input, not to ") +
                         inputFormatName(format) + " " + path.string() +
                         (objects ? " (select its objects with an object pattern)" : ""));
  if (!dicom && !options.referenceSeries.empty())
    return makeError(Errc::InvalidArgument, std::string("a reference series applies to DICOM RTSTRUCT input, not to ") +
                                                inputFormatName(format) + " " + path.string());
  if (!objects && !options.objectPatterns.empty())
    return makeError(Errc::InvalidArgument, std::string("object selection applies to Reconstruct and IMOD input, not to ") +
                                                inputFormatName(format) + " " + path.string() +
                                                (dicom ? " (select its ROIs with an ROI pattern)" : ""));
  return {};
}

// An input is a regular file (a link to one is fine) that fits in memory: a link to
// /dev/zero read gigabytes, and a FIFO with no writer hung the run. Reading a file takes a few
// times its size while it is parsed, so one larger than a quarter of the memory available is
// refused before it is read.
Result<void> checkInputFile(const std::filesystem::path& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec) return makeError(Errc::Io, "cannot read " + path.string() + ": " + ec.message());
  if (status.type() != std::filesystem::file_type::regular)
    return makeError(Errc::InvalidInput, path.string() +
                                             ": not a regular file (a directory, device, FIFO or socket); "
                                             "scansurf reads contour files");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  const HostMemory memory = availableHostMemory();
  if (!ec && memory.bytes > 0 && size > memory.bytes / 4)
    return makeError(Errc::ResourceLimit, path.string() + ": " + formatBytes(size) + " to read, more than a quarter of the " +
                                              formatBytes(memory.bytes) + " of memory available (" + memory.source + ")");
  return {};
}

// The input file, for the report's hashes (a Reconstruct series lists its own).
Result<ContourSet> withFiles(Result<ContourSet> contours, const std::filesystem::path& path) {
  if (contours && contours->files.empty()) contours->files.push_back(path.string());
  return contours;
}

// Each surfaced object's number, for the report.
void numberObjects(const std::vector<ObjectInfo>& objects, ContourSet& contours) {
  for (const ObjectInfo& o : objects)
    if (o.feature >= 0 && static_cast<std::size_t>(o.feature) < contours.features.size())
      contours.features[static_cast<std::size_t>(o.feature)].sourceNumber = o.number;
}

// Whether any pattern selects a segment (a Slicer segmentation's, as an RTSTRUCT's ROI names).
bool segmentSelected(const std::vector<std::string>& patterns, const std::string& name) {
  return std::any_of(patterns.begin(), patterns.end(), [&](const std::string& p) { return roiNameMatches(p, name); });
}

// Every pattern must select a segment; the error names the segments the file holds.
Result<void> checkSegmentPatterns(const ContourSet& set, const std::vector<std::string>& patterns) {
  for (const std::string& pattern : patterns) {
    if (std::any_of(set.features.begin(), set.features.end(), [&](const Feature& f) { return roiNameMatches(pattern, f.name); }))
      continue;
    std::string names;
    for (const Feature& f : set.features) names += (names.empty() ? "\"" : ", \"") + f.name + "\"";
    return makeError(Errc::InvalidArgument,
                     set.source + ": the segment pattern \"" + pattern + "\" matches no segment; the file holds " + names);
  }
  return {};
}

// A Slicer segmentation's segments that the patterns select, as an RTSTRUCT's ROIs are
// selected; the file's extent is kept so that the default grid, and so each surface, does not
// depend on the selection.
Result<ContourSet> selectSegments(ContourSet set, const std::vector<std::string>& patterns) {
  if (patterns.empty()) return set;
  SCANSURF_TRY(checkSegmentPatterns(set, patterns));
  set.fileExtent = extentOf(boundingBox(set));
  std::erase_if(set.features, [&](const Feature& f) { return !segmentSelected(patterns, f.name); });
  set.order.clear();  // the file's order named features now gone: computed again
  return set;
}

// A Slicer segmentation listed as an RTSTRUCT's ROIs: each segment numbered in file order, its
// closed contours, planes and z range, and whether the patterns select it.
Result<StructureSetInfo> listSegments(const std::filesystem::path& path, const std::vector<std::string>& patterns) {
  SCANSURF_ASSIGN_OR_RETURN(const ContourSet set, readSlicerSegmentation(path));
  SCANSURF_TRY(checkSegmentPatterns(set, patterns));
  StructureSetInfo info;
  int surfaced = 0;
  for (std::size_t i = 0; i < set.features.size(); ++i) {
    const Feature& f = set.features[i];
    RoiInfo roi;
    roi.number = static_cast<int>(i) + 1;
    roi.name = f.name;
    roi.color = f.color;
    int contours = 0;
    for (const FeatureSlice& slice : f.slices) contours += static_cast<int>(slice.contours.size());
    roi.contoursByType["CLOSED_PLANAR"] = contours;
    roi.slices = static_cast<int>(f.slices.size());
    if (!f.slices.empty()) roi.zMin = f.slices.front().z, roi.zMax = f.slices.back().z;
    roi.selected = patterns.empty() || segmentSelected(patterns, f.name);
    roi.feature = roi.selected ? surfaced++ : -1;
    info.rois.push_back(std::move(roi));
  }
  return info;
}

Result<ContourSet> readAny(const std::filesystem::path& path, const ReadOptions& options) {
  SCANSURF_TRY(checkInputFile(path));
  const InputFormat format = detectInputFormat(path);
  if (format == InputFormat::Unknown) return unrecognised(path);
  SCANSURF_TRY(checkOptionsApply(format, path, options));
  switch (format) {
    case InputFormat::RtStruct: return withFiles(readStructureSet(path, options), path);
    case InputFormat::ReconstructSeries: {
      SCANSURF_ASSIGN_OR_RETURN(ReconstructSeries series, readReconstructSeries(path, {options.objectPatterns}));
      numberObjects(series.objects, series.contours);
      series.contours.frame = CoordinateFrame::Specimen;
      return std::move(series.contours);
    }
    case InputFormat::ImodModel: {
      ImodOptions imod;
      imod.objectPatterns = options.objectPatterns;
      SCANSURF_ASSIGN_OR_RETURN(ImodModel model, readImodModel(path, imod));
      numberObjects(model.objects, model.contours);
      model.contours.frame = CoordinateFrame::Specimen;
      return withFiles(std::move(model.contours), path);
    }
    case InputFormat::SlicerSegmentation: {
      SCANSURF_ASSIGN_OR_RETURN(ContourSet segmentation, readSlicerSegmentation(path));
      return selectSegments(std::move(segmentation), options.roiPatterns);
    }
    default: return withFiles(readContoursJson(path), path);
  }
}

}  // namespace

const char* inputFormatName(InputFormat format) noexcept {
  switch (format) {
    case InputFormat::ContoursJson: return "contour-set JSON";
    case InputFormat::RtStruct: return "DICOM RTSTRUCT";
    case InputFormat::ReconstructSeries: return "Reconstruct series";
    case InputFormat::ImodModel: return "IMOD model";
    case InputFormat::SlicerSegmentation: return "3D Slicer segmentation";
    case InputFormat::Unknown: break;
  }
  return "unrecognised file";
}

InputFormat detectInputFormat(const std::filesystem::path& path) {
  if (hasDicomPreamble(path)) return InputFormat::RtStruct;
  if (hasImodMagic(path)) return InputFormat::ImodModel;
  if (looksLikeVtkXml(path)) return InputFormat::SlicerSegmentation;
  if (looksLikeReconstructXml(path)) return InputFormat::ReconstructSeries;
  std::ifstream in(path, std::ios::binary);
  char c = 0;
  while (in.get(c) && std::isspace(static_cast<unsigned char>(c))) {
  }
  if (in && c == '{') return InputFormat::ContoursJson;
  if (looksLikeDicomDataSet(path)) return InputFormat::RtStruct;
  if (lower(path.extension().string()) == ".json") return InputFormat::ContoursJson;  // its parser says what is wrong
  return InputFormat::Unknown;
}

Result<ContourSet> readContours(const std::filesystem::path& path, const ReadOptions& options) {
  return guarded("reading " + path.string(), [&] { return readAny(path, options); });
}

Result<ObjectListing> listObjects(const std::filesystem::path& path, const std::vector<std::string>& objectPatterns) {
  SCANSURF_TRY(checkInputFile(path));
  const InputFormat format = detectInputFormat(path);
  if (format == InputFormat::Unknown) return unrecognised(path);
  if (format != InputFormat::ReconstructSeries && format != InputFormat::ImodModel)
    return makeError(Errc::InvalidArgument, std::string("listing objects applies to Reconstruct and IMOD input, not to ") +
                                                inputFormatName(format) + " " + path.string());
  return guarded("reading " + path.string(), [&]() -> Result<ObjectListing> {
    ObjectListing listing;
    listing.format = format;
    if (format == InputFormat::ReconstructSeries) {
      ReconstructOptions options{objectPatterns, false};
      SCANSURF_ASSIGN_OR_RETURN(ReconstructSeries series, readReconstructSeries(path, options));
      listing.description = "Reconstruct series \"" + series.name + "\", " + std::to_string(series.sections) +
                            " sections (index " + std::to_string(series.firstIndex) + ".." + std::to_string(series.lastIndex) +
                            ")";
      listing.units = series.contours.units;
      listing.objects = std::move(series.objects);
      listing.warnings = std::move(series.contours.warnings);
    } else {
      ImodOptions options;
      options.objectPatterns = objectPatterns;
      options.requireFeatures = false;
      SCANSURF_ASSIGN_OR_RETURN(ImodModel model, readImodModel(path, options));
      listing.description = "IMOD model \"" + model.name + "\"";
      listing.units = model.contours.units;
      listing.objects = std::move(model.objects);
      listing.warnings = std::move(model.contours.warnings);
    }
    return listing;
  });
}

Result<StructureSetInfo> listRois(const std::filesystem::path& path, const std::vector<std::string>& roiPatterns) {
  const InputFormat format = detectInputFormat(path);
  if (format == InputFormat::Unknown) return unrecognised(path);
  if (format == InputFormat::SlicerSegmentation) {
    SCANSURF_TRY(checkInputFile(path));
    return listSegments(path, roiPatterns);
  }
  if (format != InputFormat::RtStruct)
    return makeError(Errc::InvalidArgument,
                     std::string("listing ROIs applies to DICOM RTSTRUCT and 3D Slicer segmentation input, not to ") +
                         inputFormatName(format) + " " + path.string());
  RtStructOptions options;
  options.roiPatterns = roiPatterns;
  options.requireFeatures = false;
  return guarded("reading " + path.string(), [&]() -> Result<StructureSetInfo> {
    SCANSURF_ASSIGN_OR_RETURN(RtStructure rt, readRtStruct(path, options));
    return StructureSetInfo{std::move(rt.label), std::move(rt.rois)};
  });
}

Result<void> writeContours(const ContourSet& contours, const std::filesystem::path& path) {
  return writeContoursJson(contours, path);
}

}  // namespace scansurf
