// DICOM Segmentation writer (PS3.3 A.51 Segmentation IOD, C.8.20 Segmentation Image Module,
// C.7.6.16 functional groups) with DCMTK's dcmseg: segments, frames and functional groups are
// built through its API, which checks the object before it is written.
#include "io/dicom_seg_writer.h"
#include "io/slicer_terminology.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcbytstr.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcuid.h>
#include <dcmtk/dcmfg/fgderimg.h>
#include <dcmtk/dcmfg/fgfracon.h>
#include <dcmtk/dcmfg/fgpixmsr.h>
#include <dcmtk/dcmfg/fgplanor.h>
#include <dcmtk/dcmfg/fgplanpo.h>
#include <dcmtk/dcmiod/cielabutil.h>
#include <dcmtk/dcmiod/iodmacro.h>
#include <dcmtk/dcmiod/modcommoninstanceref.h>
#include <dcmtk/dcmseg/segdoc.h>
#include <dcmtk/dcmseg/segment.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <mutex>
#include <string>
#include <utility>

#include "geometry/contours/validate.h"
#include "io/atomic_file.h"
#include "io/dicom_common.h"
#include "scansurf/palette.h"
#include "scansurf/version.h"

namespace scansurf {
namespace {

// Grid and CT agree within this (mm, or a fraction of a pixel for the lattice offset).
constexpr double kLatticeTolerance = 1e-3;

Unexpected dcmtkError(const std::string& what, const OFCondition& condition) {
  return makeError(Errc::Internal, "DICOM SEG: DCMTK refused " + what + " (" + condition.text() + ")");
}

// A Decimal String (DS) value: at most 16 characters, as exact as they allow.
std::string decimalString(double value) {
  if (value == 0) return "0";
  char buffer[64];
  for (int digits = 16; digits > 0; --digits) {
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
    if (std::char_traits<char>::length(buffer) <= 16) break;
  }
  return buffer;
}

// A Long String (LO): at most 64 characters, no backslash or control characters.
std::string longString(const std::string& text) {
  std::string out;
  for (unsigned char c : text) out += c == '\\' ? '/' : (c < 0x20 ? ' ' : static_cast<char>(c));
  if (out.size() > 64) {
    out.resize(64);
    while (!out.empty() && (static_cast<unsigned char>(out.back()) & 0xC0) == 0x80) out.pop_back();  // a cut UTF-8 character
    if (!out.empty() && (static_cast<unsigned char>(out.back()) & 0x80)) out.pop_back();
  }
  return out.empty() ? std::string("unnamed") : out;
}

// Where the CT's voxels lie in the label volume's grid.
struct CtInGrid {
  int offsetX = 0, offsetY = 0;  // grid column and row of CT pixel (0, 0)
  std::vector<int> layer;        // grid layer of each CT slice
};

Result<CtInGrid> locateCt(const Grid& g, const CtSeries& ct) {
  auto notOnLattice = [&](const std::string& why) {
    return makeError(Errc::InvalidArgument, "DICOM SEG: the label volume is not on the voxel lattice of the reference series " +
                                                ct.directory + " (" + why +
                                                "); build it on the reference grid (no voxel size or grid counts)");
  };
  if (std::abs(g.spacingX - ct.spacingX) > kLatticeTolerance * ct.spacingX ||
      std::abs(g.spacingY - ct.spacingY) > kLatticeTolerance * ct.spacingY)
    return notOnLattice("pixel size " + formatNumber(g.spacingX) + " x " + formatNumber(g.spacingY) + " mm, the CT's " +
                        formatNumber(ct.spacingX) + " x " + formatNumber(ct.spacingY) + " mm");
  CtInGrid at;
  const double fx = (ct.originX - g.originX) / g.spacingX, fy = (ct.originY - g.originY) / g.spacingY;
  at.offsetX = static_cast<int>(std::lround(fx));
  at.offsetY = static_cast<int>(std::lround(fy));
  if (std::abs(fx - at.offsetX) > kLatticeTolerance || std::abs(fy - at.offsetY) > kLatticeTolerance || at.offsetX < 0 ||
      at.offsetY < 0 || at.offsetX + ct.columns > g.nx || at.offsetY + ct.rows > g.ny)
    return notOnLattice("its pixels do not cover the CT's");
  // Each CT slice takes the layer whose slab holds it: CT slices between contour planes take
  // the nearer plane's masks (the slab rule), those beyond the planes the background padding.
  for (double z : ct.sliceZ) at.layer.push_back(nearestLayer(g, z));
  return at;
}

struct DatasetValues {
  std::string sliceThickness, seriesNumber;
};

DatasetValues valuesOf(DcmDataset& ds, const CtSeries& ct) {
  DatasetValues v;
  Float64 thickness = 0;
  if (ds.findAndGetFloat64(DCM_SliceThickness, thickness).good() && thickness > 0 && std::isfinite(thickness)) {
    v.sliceThickness = decimalString(thickness);
  } else {  // the smallest slice gap, else the pixel size
    double gap = 0;
    for (std::size_t k = 1; k < ct.sliceZ.size(); ++k)
      gap = k == 1 ? ct.sliceZ[1] - ct.sliceZ[0] : std::min(gap, ct.sliceZ[k] - ct.sliceZ[k - 1]);
    v.sliceThickness = decimalString(gap > 0 ? gap : std::max(ct.spacingX, ct.spacingY));
  }
  Sint32 number = 0;
  v.seriesNumber = std::to_string(
      ds.findAndGetSint32(DCM_SeriesNumber, number).good() && number >= 0 && number < 1000000 ? number + 1000 : 1000);
  return v;
}

Result<void> checkSegInputs(const std::vector<LabelVolume>& layers, const CtSeries& ct) {
  if (layers.empty()) return makeError(Errc::InvalidArgument, "DICOM SEG: no label volume");
  const Grid& g = layers.front().grid;
  for (const LabelVolume& volume : layers)
    if (volume.labels.size() != g.voxelCount() || volume.grid.nx != g.nx || volume.grid.ny != g.ny || volume.grid.nz != g.nz)
      return makeError(Errc::InvalidArgument, "DICOM SEG: the label volumes have " + std::to_string(volume.labels.size()) +
                                                  " labels for a grid of " + std::to_string(g.voxelCount()) + " voxels");
  if (ct.sliceZ.empty() || ct.sopInstanceUids.size() != ct.sliceZ.size() || ct.sopClassUids.size() != ct.sliceZ.size())
    return makeError(Errc::InvalidArgument, "DICOM SEG: the reference series " + ct.directory + " has no images");
  if (ct.rows > 65535 || ct.columns > 65535)
    return makeError(Errc::InvalidInput, "DICOM SEG: the CT's images are larger than 65535 pixels");
  return {};
}

// Which feature has voxels on which CT slice, how many in all and how many on the CT.
struct VoxelCensus {
  std::vector<std::vector<char>> present;  // per feature, per CT slice
  std::vector<std::size_t> inside, total, layerOf;
};

VoxelCensus countVoxels(std::size_t featureCount, const std::vector<LabelVolume>& layers, const CtSeries& ct,
                        const CtInGrid& at) {
  const std::size_t slices = ct.sliceZ.size();
  VoxelCensus n{std::vector<std::vector<char>>(featureCount, std::vector<char>(slices, 0)),
                std::vector<std::size_t>(featureCount, 0), std::vector<std::size_t>(featureCount, 0),
                std::vector<std::size_t>(featureCount, 0)};
  for (std::size_t layer = 0; layer < layers.size(); ++layer)
    for (Label l : layers[layer].labels)
      if (l != kBackground && static_cast<std::size_t>(l) <= featureCount) {
        ++n.total[static_cast<std::size_t>(featureOfLabel(l))];
        n.layerOf[static_cast<std::size_t>(featureOfLabel(l))] = layer;  // each feature is in one layer
      }
  for (const LabelVolume& volume : layers)
    for (std::size_t k = 0; k < slices; ++k)
      for (int j = 0; j < ct.rows; ++j)
        for (int i = 0; i < ct.columns; ++i) {
          const Label l = volume.at(at.offsetX + i, at.offsetY + j, at.layer[k]);
          if (l == kBackground || static_cast<std::size_t>(l) > featureCount) continue;
          const auto f = static_cast<std::size_t>(featureOfLabel(l));
          ++n.inside[f];
          n.present[f][k] = 1;
        }
  return n;
}

// The features that get a segment (voxels on the CT's grid), with a warning for the others
// and for voxels beyond the CT.
std::vector<std::size_t> segmentFeaturesOf(const ContourSet& contours, const VoxelCensus& n, std::vector<std::string>& warnings) {
  std::vector<std::size_t> features;
  for (std::size_t f = 0; f < contours.features.size(); ++f) {
    const std::string& name = contours.features[f].name;
    if (n.inside[f] == 0) {
      warnings.push_back("feature \"" + name + "\" has no voxel on the CT's grid: no segment for it in the DICOM SEG");
      continue;
    }
    if (n.total[f] > n.inside[f])
      warnings.push_back("feature \"" + name + "\": " + std::to_string(n.total[f] - n.inside[f]) +
                         " voxel(s) beyond the CT's field of view are not in the DICOM SEG");
    features.push_back(f);
  }
  return features;
}

// The document, with patient, study and frame of reference from the first CT image, and
// scansurf as the equipment and the series.
Result<std::unique_ptr<DcmSegmentation>> createDocument(DcmItem& firstCt, const CtSeries& ct, const DatasetValues& values) {
  const IODGeneralEquipmentModule::EquipmentInfo equipment("scansurf", "scansurf", "1", SCANSURF_VERSION_STRING);
  const ContentIdentificationMacro content("1", "SCANSURF", "scansurf label volume from planar contours", "");
  DcmSegmentation* created = nullptr;
  OFCondition c = DcmSegmentation::createBinarySegmentation(created, static_cast<Uint16>(ct.rows),
                                                            static_cast<Uint16>(ct.columns), equipment, content);
  std::unique_ptr<DcmSegmentation> seg(created);
  if (c.bad() || !seg) return dcmtkError("a binary segmentation", c);
  if ((c = seg->importFromSourceImage(firstCt)).bad()) return dcmtkError("the CT's patient and study", c);
  // The import also copies the CT's General Equipment (institution, station, ...): the SEG's
  // equipment is scansurf.
  seg->getEquipment().clearData();
  if ((c = seg->setEquipmentInfo(equipment)).bad()) return dcmtkError("the equipment", c);
  seg->getSeries().setSeriesDescription("scansurf segmentation");
  // Names and the CT's text are UTF-8 (decodeTextToUtf8).
  if ((c = seg->getSOPCommon().setSpecificCharacterSet("ISO_IR 192")).bad()) return dcmtkError("the character set", c);
  seg->getSeries().setSeriesNumber(values.seriesNumber.c_str());
  return seg;
}

// Dimensions (segment, then slice position: PS3.3 C.8.20.2.3's recommended pair) and the
// shared functional groups: axial orientation (readCtSeries accepts no other) and the CT's
// pixel measures.
Result<void> addDimensionsAndSharedGroups(DcmSegmentation& seg, const CtSeries& ct, const DatasetValues& values) {
  char dimensionUid[100];
  dcmGenerateUniqueIdentifier(dimensionUid, SITE_INSTANCE_UID_ROOT);
  IODMultiframeDimensionModule& dimensions = seg.getDimensions();
  OFCondition c;
  if ((c = dimensions.addDimensionIndex(DCM_ReferencedSegmentNumber, dimensionUid, DCM_SegmentIdentificationSequence,
                                        "ReferencedSegmentNumber"))
          .bad() ||
      (c = dimensions.addDimensionIndex(DCM_ImagePositionPatient, dimensionUid, DCM_PlanePositionSequence,
                                        "ImagePositionPatient"))
          .bad())
    return dcmtkError("the dimension indices", c);
  std::unique_ptr<FGPlaneOrientationPatient> orientation(FGPlaneOrientationPatient::createMinimal("1", "0", "0", "0", "1", "0"));
  FGPixelMeasures measures;
  if (!orientation || (c = seg.addForAllFrames(*orientation)).bad()) return dcmtkError("the plane orientation", c);
  const std::string spacing = decimalString(ct.spacingY) + "\\" + decimalString(ct.spacingX);  // row\column spacing
  if ((c = measures.setPixelSpacing(spacing.c_str())).bad() ||
      (c = measures.setSliceThickness(values.sliceThickness.c_str())).bad() || (c = seg.addForAllFrames(measures)).bad())
    return dcmtkError("the pixel measures", c);
  return {};
}

// One segment per feature with voxels, named and coloured; returns their segment numbers.
Result<std::vector<Uint16>> addSegments(DcmSegmentation& seg, const ContourSet& contours,
                                        const std::vector<std::size_t>& features) {
  const std::vector<Rgb> colors = featureColors(contours);
  std::vector<Uint16> numbers;
  for (std::size_t f : features) {
    const SegmentTerminology t = terminologyOf(contours.features[f].interpretedType);
    const CodeSequenceMacro category(t.category.value, t.category.scheme, t.category.meaning);
    const CodeSequenceMacro type(t.type.value, t.type.scheme, t.type.meaning);
    DcmSegment* created = nullptr;
    const std::string label = longString(contours.features[f].name);
    // DCMTK checks a new segment's label as ASCII: created with a placeholder, then given its
    // UTF-8 name (the document says ISO_IR 192).
    OFCondition c = DcmSegment::create(created, "segment", category, type, DcmSegTypes::SAT_AUTOMATIC, "scansurf");
    std::unique_ptr<DcmSegment> segment(created);
    if (c.bad() || !segment || (c = segment->setSegmentLabel(label.c_str(), OFFalse)).bad())
      return dcmtkError("segment \"" + label + "\"", c);
    double lab[3];
    IODCIELabUtil::rgb2DicomLab(lab[0], lab[1], lab[2], colors[f][0] / 255.0, colors[f][1] / 255.0, colors[f][2] / 255.0);
    Uint16 scaled[3];
    for (int i = 0; i < 3; ++i) scaled[i] = static_cast<Uint16>(std::clamp(std::lround(lab[i]), 0L, 65535L));
    if ((c = segment->setRecommendedDisplayCIELabValue(scaled[0], scaled[1], scaled[2])).bad())
      return dcmtkError("the colour of segment \"" + label + "\"", c);
    Uint16 number = 0;
    if ((c = seg.addSegment(segment.get(), number)).bad()) return dcmtkError("segment \"" + label + "\"", c);
    segment.release();  // the segmentation owns it now
    numbers.push_back(number);
  }
  return numbers;
}

// One frame's per-frame functional groups: its position, its dimension index values, and the
// CT image it derives from; then the frame itself.
Result<void> addFrame(DcmSegmentation& seg, std::vector<Uint8>& mask, Uint16 segmentNumber, std::size_t k, const CtSeries& ct) {
  const std::string x = decimalString(ct.originX), y = decimalString(ct.originY);
  std::unique_ptr<FGPlanePosPatient> position(
      FGPlanePosPatient::createMinimal(x.c_str(), y.c_str(), decimalString(ct.sliceZ[k]).c_str()));
  FGFrameContent frameContent;
  ImageSOPInstanceReferenceMacro source;
  OFCondition c;
  if (!position || (c = frameContent.setDimensionIndexValues(segmentNumber, 0)).bad() ||
      (c = frameContent.setDimensionIndexValues(static_cast<Uint32>(k + 1), 1)).bad() ||
      (c = source.setReferencedSOPClassUID(ct.sopClassUids[k].c_str())).bad() ||
      (c = source.setReferencedSOPInstanceUID(ct.sopInstanceUids[k].c_str())).bad())
    return dcmtkError("the functional groups of a frame", c);
  OFVector<ImageSOPInstanceReferenceMacro> sources;
  sources.push_back(source);
  std::unique_ptr<FGDerivationImage> derivation(
      DcmSegmentation::createDerivationImageFG(sources, "scansurf: scan conversion of planar contours"));
  if (!derivation) return makeError(Errc::Internal, "DICOM SEG: DCMTK refused the derivation image of a frame");
  OFVector<FGBase*> perFrame;
  perFrame.push_back(position.get());
  perFrame.push_back(&frameContent);
  perFrame.push_back(derivation.get());
  if ((c = seg.addFrame(mask.data(), segmentNumber, perFrame)).bad()) return dcmtkError("a frame", c);
  return {};
}

// Frames: per segment, each CT slice it has voxels on, in increasing z. Returns their count.
Result<int> addFrames(DcmSegmentation& seg, const std::vector<LabelVolume>& layers, const VoxelCensus& n, const CtInGrid& at,
                      const CtSeries& ct, const std::vector<std::size_t>& features, const std::vector<Uint16>& numbers) {
  std::vector<Uint8> mask(static_cast<std::size_t>(ct.rows) * static_cast<std::size_t>(ct.columns));
  int frames = 0;
  for (std::size_t s = 0; s < features.size(); ++s) {
    const std::size_t f = features[s];
    const Label label = labelOfFeature(static_cast<int>(f));
    const LabelVolume& volume = layers[n.layerOf[f]];
    for (std::size_t k = 0; k < ct.sliceZ.size(); ++k) {
      if (!n.present[f][k]) continue;
      for (int j = 0; j < ct.rows; ++j)
        for (int i = 0; i < ct.columns; ++i)
          mask[static_cast<std::size_t>(j) * static_cast<std::size_t>(ct.columns) + static_cast<std::size_t>(i)] =
              volume.at(at.offsetX + i, at.offsetY + j, at.layer[k]) == label ? 1 : 0;
      SCANSURF_TRY(addFrame(seg, mask, numbers[s], k, ct));
      ++frames;
    }
  }
  return frames;
}

// Every CT image, in the Common Instance Reference Module's Referenced Series Sequence.
Result<void> addReferencedSeries(DcmSegmentation& seg, const CtSeries& ct) {
  auto series = std::make_unique<IODSeriesAndInstanceReferenceMacro::ReferencedSeriesItem>();
  OFCondition c;
  if ((c = series->setSeriesInstanceUID(ct.seriesUid.c_str())).bad()) return dcmtkError("the CT's Series Instance UID", c);
  for (std::size_t k = 0; k < ct.sliceZ.size(); ++k)
    if ((c = series->addReference(ct.sopClassUids[k].c_str(), ct.sopInstanceUids[k].c_str())).bad())
      return dcmtkError("the reference to " + ct.files[k], c);
  seg.getCommonInstanceReference().getReferencedSeriesItems().push_back(series.release());
  return {};
}

// The Patient (C.7.1.1, de-identification included), Clinical Trial Subject and Study, General
// Study (C.7.2.1) and Patient Study (C.7.2.2) attributes: the SEG belongs to the CT's patient
// and study, and says so as completely as the CT does (DCMTK's import keeps only its own
// modules' attributes, which leaves out e.g. Study Description and Patient Identity Removed).
constexpr std::pair<Uint16, Uint16> kPatientAndStudyTags[] = {
    {0x0008, 0x0005},  // Specific Character Set: the copied names are in the CT's
    // Patient
    {0x0010, 0x0010},
    {0x0010, 0x0020},
    {0x0010, 0x0021},
    {0x0010, 0x0022},
    {0x0010, 0x0024},
    {0x0010, 0x0030},
    {0x0010, 0x0032},
    {0x0010, 0x0040},
    {0x0010, 0x0200},
    {0x0010, 0x1001},
    {0x0010, 0x1002},
    {0x0010, 0x1100},
    {0x0010, 0x2160},
    {0x0010, 0x2201},
    {0x0010, 0x2202},
    {0x0010, 0x2292},
    {0x0010, 0x2293},
    {0x0010, 0x2294},
    {0x0010, 0x2297},
    {0x0010, 0x2298},
    {0x0010, 0x2299},
    {0x0010, 0x4000},
    {0x0012, 0x0062},
    {0x0012, 0x0063},
    {0x0012, 0x0064},  // Patient Identity Removed, De-identification Method (Code Sequence)
    // Clinical Trial Subject and Study
    {0x0012, 0x0010},
    {0x0012, 0x0020},
    {0x0012, 0x0021},
    {0x0012, 0x0030},
    {0x0012, 0x0031},
    {0x0012, 0x0040},
    {0x0012, 0x0042},
    {0x0012, 0x0050},
    {0x0012, 0x0051},
    // General Study
    {0x0020, 0x000D},
    {0x0008, 0x0020},
    {0x0008, 0x0030},
    {0x0008, 0x0090},
    {0x0008, 0x0096},
    {0x0008, 0x009C},
    {0x0020, 0x0010},
    {0x0008, 0x0050},
    {0x0008, 0x0051},
    {0x0008, 0x1030},
    {0x0008, 0x1048},
    {0x0008, 0x1049},
    {0x0008, 0x1060},
    {0x0008, 0x1062},
    {0x0032, 0x1034},
    {0x0008, 0x1110},
    {0x0008, 0x1032},
    {0x0040, 0x1012},
    // Patient Study
    {0x0008, 0x1080},
    {0x0008, 0x1084},
    {0x0010, 0x1010},
    {0x0010, 0x1020},
    {0x0010, 0x1021},
    {0x0010, 0x1030},
    {0x0010, 0x2180},
    {0x0010, 0x21B0},
    {0x0038, 0x0010},
    {0x0038, 0x0014},
    {0x0038, 0x0060},
    {0x0038, 0x0062},
    {0x0010, 0x2203},
    {0x0010, 0x21A0},
    {0x0010, 0x21C0},
    {0x0010, 0x21D0},
    {0x0038, 0x0500}};

// Each of those the CT has and the SEG lacks (or holds empty), copied; one the CT has empty
// too, so that both instances of the study say the same (dcentvfy compares them).
Result<void> copyPatientAndStudy(DcmItem& ct, DcmItem& seg) {
  for (const auto& [group, element] : kPatientAndStudyTags) {
    const DcmTagKey tag(group, element);
    DcmElement* source = nullptr;
    if (ct.findAndGetElement(tag, source).bad() || !source) continue;
    DcmElement* present = nullptr;
    if (seg.findAndGetElement(tag, present).good() && present && (!present->isEmpty() || source->isEmpty())) continue;
    if (const OFCondition c = seg.insert(static_cast<DcmElement*>(source->clone()), OFTrue); c.bad())
      return dcmtkError("the CT's " + std::string(DcmTag(tag).getTagName()), c);
  }
  return {};
}

// DCMTK's IOD classes check each string they copy and write as ASCII (they pass no character
// set to the check); the document's text is UTF-8 under ISO_IR 192, so the VR checker's
// character test is off while the document is made and written, and restored after.
// The setting is the process's: one document at a time (Python writes on several threads).
class Utf8Strings {
 public:
  Utf8Strings() : hold_(mutex()), was_(dcmEnableVRCheckerForStringValues.get()) {
    dcmEnableVRCheckerForStringValues.set(OFFalse);
  }
  ~Utf8Strings() { dcmEnableVRCheckerForStringValues.set(was_); }
  Utf8Strings(const Utf8Strings&) = delete;
  Utf8Strings& operator=(const Utf8Strings&) = delete;

 private:
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  std::lock_guard<std::mutex> hold_;
  OFBool was_;
};

Result<void> saveSegmentation(DcmSegmentation& seg, DcmItem& firstCt, const std::filesystem::path& path) {
  DcmFileFormat file;
  if (const OFCondition c = seg.writeDataset(*file.getDataset()); c.bad()) return dcmtkError("the Segmentation", c);
  SCANSURF_TRY(copyPatientAndStudy(firstCt, *file.getDataset()));
  return writeThroughTemporaryPath(path, ".dcm", [&](const std::filesystem::path& temp) -> Result<void> {
    const OFCondition saved = file.saveFile(temp.c_str(), EXS_LittleEndianExplicit);
    if (saved.bad()) return makeError(Errc::Io, "cannot write '" + path.string() + "': " + saved.text());
    return {};
  });
}

}  // namespace

Result<DicomSegSummary> writeDicomSegmentation(const std::filesystem::path& path, const ContourSet& contours,
                                               const std::vector<LabelVolume>& layers, const CtSeries& ct) {
  SCANSURF_TRY(checkSegInputs(layers, ct));
  SCANSURF_ASSIGN_OR_RETURN(const CtInGrid at, locateCt(layers.front().grid, ct));
  const VoxelCensus census = countVoxels(contours.features.size(), layers, ct, at);
  DicomSegSummary written;
  const std::vector<std::size_t> features = segmentFeaturesOf(contours, census, written.warnings);
  if (features.empty())
    return makeError(Errc::InvalidInput, "DICOM SEG: no feature has a voxel on the CT's grid (" + ct.directory +
                                             "); nothing to write to " + path.string());
  SCANSURF_ASSIGN_OR_RETURN(DicomFile first, loadDicomFile(ct.files.front(), /*stopAtPixelData=*/true));
  decodeTextToUtf8(ct.files.front(), first.dataset(), written.warnings);
  const Utf8Strings utf8;
  const DatasetValues values = valuesOf(first.dataset(), ct);
  SCANSURF_ASSIGN_OR_RETURN(std::unique_ptr<DcmSegmentation> seg, createDocument(first.dataset(), ct, values));
  SCANSURF_TRY(addDimensionsAndSharedGroups(*seg, ct, values));
  SCANSURF_ASSIGN_OR_RETURN(const std::vector<Uint16> numbers, addSegments(*seg, contours, features));
  SCANSURF_ASSIGN_OR_RETURN(written.frames, addFrames(*seg, layers, census, at, ct, features, numbers));
  written.segments = static_cast<int>(numbers.size());
  SCANSURF_TRY(addReferencedSeries(*seg, ct));
  SCANSURF_TRY(saveSegmentation(*seg, first.dataset(), path));
  return written;
}

}  // namespace scansurf
