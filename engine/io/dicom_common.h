// scansurf: loading DICOM files with DCMTK (shared by the RTSTRUCT and CT series readers).
// Internal: DCMTK types stay inside engine/io.
#pragma once

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcfilefo.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "scansurf/result.h"

namespace scansurf {

struct DicomFile {
  std::unique_ptr<DcmFileFormat> fileFormat = std::make_unique<DcmFileFormat>();
  DcmFileFormat& file() { return *fileFormat; }
  DcmDataset& dataset() { return *fileFormat->getDataset(); }
};

// Loads a DICOM file with or without its Part 10 file header; with stopAtPixelData only the
// attributes before Pixel Data are parsed. DCMTK's own log output is switched off (errors come
// back as Results). Errors: Errc::Io when the file cannot be opened; Errc::InvalidInput when it
// is not DICOM (no "DICM" preamble and no readable data set with a SOP Class UID or Modality)
// or its DICOM structure is corrupt; Errc::Internal when DCMTK's data dictionary is missing.
Result<DicomFile> loadDicomFile(const std::filesystem::path& path, bool stopAtPixelData = false);

// Whether a file without the Part 10 header starts like a DICOM data set (its first element in
// group 0002 or 0008, with an explicit VR or an implicit length that fits the file).
bool looksLikeDicomDataSet(const std::filesystem::path& path);

// Every text value of the data set in UTF-8 (its Specific Character Set then says ISO_IR 192):
// converted from the set it declares by DCMTK. Bytes the set does not allow (beyond ASCII
// without one, as some systems write Latin-1 names) or a set that cannot be converted are read
// as Latin-1 (ISO_IR 100), the common single-byte set, with a warning naming the file.
void decodeTextToUtf8(const std::string& file, DcmDataset& dataset, std::vector<std::string>& warnings);

}  // namespace scansurf
