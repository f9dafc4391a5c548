// scansurf: loading DICOM files with DCMTK.
#include "io/dicom_common.h"

#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcdict.h>
#include <dcmtk/dcmdata/dcvr.h>
#include <dcmtk/oflog/oflog.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <mutex>
#include <string>

#include "io/dicom_nesting.h"
#include "io/rtstruct_reader.h"

namespace scansurf {

Result<DicomFile> loadDicomFile(const std::filesystem::path& path, bool stopAtPixelData) {
  static std::once_flag quietLogs;
  // DCMTK logs parser warnings to stderr by default; a library reports through its Results.
  // A value longer than 64 KiB (a long Contour Data) cannot keep its 16-bit-length VR in explicit
  // VR; writers then store it as UN. Read such values with the VR the dictionary gives the tag.
  std::call_once(quietLogs, [] {
    OFLog::configure(OFLogger::OFF_LOG_LEVEL);
    dcmEnableUnknownVRConversion.set(OFTrue);
  });
  const std::string file = path.string();
  if (!std::ifstream(path, std::ios::binary).is_open()) return makeError(Errc::Io, file + ": cannot open the file");
  if (std::filesystem::is_directory(path)) return makeError(Errc::Io, file + ": is a directory, not a file");
  if (!dcmDataDict.isDictionaryLoaded())
    return makeError(Errc::Internal, "DCMTK's DICOM data dictionary is not loaded (is libdcmtk installed? see DCMDICTPATH)");

  // DCMTK's parser recurses into sequences: a hostile nesting depth would overflow the stack.
  SCANSURF_TRY(checkDicomNesting(path, stopAtPixelData));
  const bool preamble = hasDicomPreamble(path);
  DicomFile dicom;
  const OFCondition status =
      dicom.file().loadFileUntilTag(file.c_str(), EXS_Unknown, EGL_noChange, DCM_MaxReadLength, ERM_autoDetect,
                                    stopAtPixelData ? DcmTagKey(DCM_PixelData) : DcmTagKey(DCM_UndefinedTagKey));
  if (status.bad()) {
    if (!preamble) return makeError(Errc::InvalidInput, file + ": not a DICOM file");
    return makeError(Errc::InvalidInput, file + ": corrupt DICOM file (" + std::string(status.text()) + ")");
  }
  // Without the preamble DCMTK parses any bytes as a data set; a real one names its kind.
  if (!dicom.dataset().tagExistsWithValue(DCM_SOPClassUID) && !dicom.dataset().tagExistsWithValue(DCM_Modality))
    return makeError(
        Errc::InvalidInput,
        file + (preamble ? ": DICOM file without SOP Class UID (0008,0016) or Modality (0008,0060)" : ": not a DICOM file"));
  return dicom;
}

// A DICOM data set without the Part 10 header starts with its first data element: group
// 0002 (meta information) or 0008 (the identifying group every IOD begins with), little
// endian, then either an explicit VR (two upper-case letters of a known VR) or an implicit
// VR's 32-bit length that fits the file.
bool looksLikeDicomDataSet(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  const auto size = static_cast<std::uint64_t>(std::max<std::streamoff>(0, in.tellg()));
  in.seekg(0);
  unsigned char b[8];
  if (!in.read(reinterpret_cast<char*>(b), sizeof b)) return false;
  const unsigned group = b[0] | (b[1] << 8);
  if (group != 0x0002 && group != 0x0008) return false;
  static constexpr const char* kVrs[] = {"AE", "AS", "AT", "CS", "DA", "DS", "DT", "FD", "FL", "IS", "LO", "LT",
                                         "OB", "OD", "OF", "OL", "OV", "OW", "PN", "SH", "SL", "SQ", "SS", "ST",
                                         "SV", "TM", "UC", "UI", "UL", "UN", "UR", "US", "UT", "UV"};
  const std::string vr{static_cast<char>(b[4]), static_cast<char>(b[5])};
  if (std::find(std::begin(kVrs), std::end(kVrs), vr) != std::end(kVrs)) return true;
  const std::uint64_t length = b[4] | (b[5] << 8) | (b[6] << 16) | (static_cast<std::uint64_t>(b[7]) << 24);
  return length == 0xFFFFFFFFu || length <= size - 8;
}

void decodeTextToUtf8(const std::string& file, DcmDataset& dataset, std::vector<std::string>& warnings) {
  OFString charset;
  dataset.findAndGetOFStringArray(DCM_SpecificCharacterSet, charset);
  DcmDataset converted(dataset);  // a failed conversion may have changed some values: keep none of it
  if (converted.convertToUTF8().good()) {
    dataset = converted;
    return;
  }
  const std::string declared = charset.empty() ? "none, so ASCII" : "'" + std::string(charset.c_str()) + "'";
  if (dataset.convertCharacterSet("ISO_IR 100", "ISO_IR 192", 0, OFTrue).good())
    warnings.push_back(file + ": text that its Specific Character Set (" + declared +
                       ") does not allow; read as Latin-1 (ISO_IR 100)");
  else
    warnings.push_back(file + ": text that could not be read in its Specific Character Set (" + declared + ")");
}

}  // namespace scansurf
