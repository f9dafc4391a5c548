// scansurf: the classified label volume as NIfTI-1 (nifti.nimh.nih.gov/nifti-1), written by
// the NIfTI reference library (Debian's libnifti2-dev: nifti1_io + znzlib), and its label table
// in ITK-SNAP's label description format.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "io/nrrd_writer.h"
#include "scansurf/result.h"

namespace scansurf {

// NIfTI's world space is RAS ("+x = Right  +y = Anterior  +z = Superior", nifti1.h), while
// scansurf's coordinates are DICOM patient LPS (+x = Left, +y = Posterior, +z = Superior). The
// voxel-to-world matrix is therefore diag(-1, -1, 1) times the LPS geometry: voxel (i, j, k)
// lies at RAS (-x, -y, z) where (x, y, z) is its LPS centre.
struct NiftiAffine {
  double m[3][4] = {};  // rows x, y, z of the 3x4 voxel -> RAS mm matrix
};
NiftiAffine rasAffineOf(const NrrdGeometry& geometry);

// Writes a NIfTI-1 single file: gzip-compressed when the name ends in .nii.gz (nifti's znzlib
// decides by the name), uncompressed for .nii. 3D, DT_UINT8 when every label fits, else
// DT_UINT16; intent NIFTI_INTENT_LABEL; cal_min 0 and cal_max the largest label; pixdim the
// voxel steps; qform and sform both the RAS matrix above with code NIFTI_XFORM_SCANNER_ANAT
// (NIfTI-1 keeps them as float32); xyz units from `units` ("mm", "um", "m"; anything else is
// NIFTI_UNITS_UNKNOWN). The library has no error status, so the file is read back with it and
// compared before it is renamed into place. Errors: Errc::InvalidArgument when the volume is
// empty or its axes are not diagonal; Errc::Io naming the path.
Result<void> writeNifti(const std::filesystem::path& path, const RegularLabelVolume& volume, const std::string& units);

// Writes the label table in ITK-SNAP's label description format (`IDX R G B A VIS MSH "LABEL"`
// per line, 0 = "Clear Label", then one line per feature; '"' in a name becomes '\''),
// which ITK-SNAP reads with Segmentation > Import Label Descriptions. Replaced atomically.
// Errors: Errc::Io naming the path.
Result<void> writeItkSnapLabels(const std::filesystem::path& path, const std::vector<LabelEntry>& table);

// The label table beside a NIfTI volume: F.nii.gz and F.nii -> F.label.txt.
std::filesystem::path itkSnapLabelPathFor(const std::filesystem::path& niftiPath);

}  // namespace scansurf
