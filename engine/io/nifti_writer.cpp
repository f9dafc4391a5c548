// NIfTI-1 writer: the header and data are written by nifti1_io (the NIfTI reference library),
// which gzips through znzlib when the file name ends in .gz.
#include "io/nifti_writer.h"

#include <nifti1_io.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <memory>
#include <sstream>

#include "core/text_fields.h"
#include "io/atomic_file.h"
#include "scansurf/version.h"

namespace scansurf {
namespace {

struct NimDeleter {
  void operator()(nifti_image* nim) const { nifti_image_free(nim); }
};
using NimPtr = std::unique_ptr<nifti_image, NimDeleter>;

int unitsCode(const std::string& units) {
  if (units == "mm") return NIFTI_UNITS_MM;
  if (units == "um" || units == "micron" || units == "\xC2\xB5m") return NIFTI_UNITS_MICRON;
  if (units == "m") return NIFTI_UNITS_METER;
  return NIFTI_UNITS_UNKNOWN;
}

bool endsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && std::equal(tail.rbegin(), tail.rend(), s.rbegin(),
                                               [](char a, char b) { return std::tolower(static_cast<unsigned char>(a)) == b; });
}

// Copies text into a fixed-size, NUL-terminated header field.
template <std::size_t N>
void setField(char (&field)[N], const std::string& text) {
  std::snprintf(field, N, "%s", text.c_str());
}

// The file as the library reads it back equals what was meant to be written.
bool readsBackAs(const std::filesystem::path& path, const nifti_image& written) {
  NimPtr back(nifti_image_read(path.c_str(), 1));
  if (!back || !back->data) return false;
  const std::size_t bytes = static_cast<std::size_t>(written.nvox) * static_cast<std::size_t>(written.nbyper);
  return back->datatype == written.datatype && back->nx == written.nx && back->ny == written.ny && back->nz == written.nz &&
         static_cast<std::size_t>(back->nvox) * static_cast<std::size_t>(back->nbyper) == bytes &&
         std::memcmp(back->data, written.data, bytes) == 0;
}

}  // namespace

NiftiAffine rasAffineOf(const NrrdGeometry& geometry) {
  NiftiAffine a;
  static constexpr double kLpsToRas[3] = {-1, -1, 1};
  for (int row = 0; row < 3; ++row) {
    for (int axis = 0; axis < 3; ++axis)
      a.m[row][axis] = kLpsToRas[row] * geometry.axes[static_cast<std::size_t>(axis)][static_cast<std::size_t>(row)];
    a.m[row][3] = kLpsToRas[row] * geometry.origin[static_cast<std::size_t>(row)];
  }
  return a;
}

Result<void> writeNifti(const std::filesystem::path& path, const RegularLabelVolume& volume, const std::string& units) {
  const std::size_t count =
      static_cast<std::size_t>(volume.nx) * static_cast<std::size_t>(volume.ny) * static_cast<std::size_t>(volume.nz);
  if (volume.nx < 1 || volume.ny < 1 || volume.nz < 1 || volume.labels.size() != count)
    return makeError(Errc::InvalidArgument, "cannot write '" + path.string() + "': the label volume is empty or inconsistent");
  const Label maxLabel = *std::max_element(volume.labels.begin(), volume.labels.end());
  const bool bytes = maxLabel < 256;

  const int dims[8] = {3, volume.nx, volume.ny, volume.nz, 1, 1, 1, 1};
  NimPtr nim(nifti_make_new_nim(dims, bytes ? DT_UINT8 : DT_UINT16, 1));
  if (!nim || !nim->data)
    return makeError(Errc::OutOfMemory, "cannot write '" + path.string() + "': no memory for the NIfTI image");
  if (bytes)
    std::copy(volume.labels.begin(), volume.labels.end(), static_cast<std::uint8_t*>(nim->data));
  else
    std::copy(volume.labels.begin(), volume.labels.end(), static_cast<std::uint16_t*>(nim->data));

  const NiftiAffine ras = rasAffineOf(volume.geometry);
  mat44 m{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) m.m[r][c] = static_cast<float>(ras.m[r][c]);
  m.m[3][3] = 1;
  // sform: the matrix itself. qform: the same as rotation + pixdim + offset (the quaternion
  // form NIfTI-1 readers such as ITK prefer), which reproduces it for orthogonal axes.
  nim->sform_code = NIFTI_XFORM_SCANNER_ANAT;
  nim->sto_xyz = m;
  nim->sto_ijk = nifti_mat44_inverse(m);
  float dx = 0, dy = 0, dz = 0, qfac = 1;
  nifti_mat44_to_quatern(m, &nim->quatern_b, &nim->quatern_c, &nim->quatern_d, &nim->qoffset_x, &nim->qoffset_y, &nim->qoffset_z,
                         &dx, &dy, &dz, &qfac);
  nim->qfac = qfac;
  nim->qform_code = NIFTI_XFORM_SCANNER_ANAT;
  nim->qto_xyz = nifti_quatern_to_mat44(nim->quatern_b, nim->quatern_c, nim->quatern_d, nim->qoffset_x, nim->qoffset_y,
                                        nim->qoffset_z, dx, dy, dz, qfac);
  nim->qto_ijk = nifti_mat44_inverse(nim->qto_xyz);
  nim->dx = nim->pixdim[1] = dx;
  nim->dy = nim->pixdim[2] = dy;
  nim->dz = nim->pixdim[3] = dz;
  nim->xyz_units = unitsCode(units);
  nim->intent_code = NIFTI_INTENT_LABEL;
  setField(nim->intent_name, "labels");
  nim->cal_min = 0;
  nim->cal_max = maxLabel;
  setField(nim->descrip, std::string("scansurf ") + SCANSURF_VERSION_STRING + " labels: feature index + 1, 0 background");

  const std::string name = path.filename().string();
  const std::string suffix = endsWith(name, ".gz") ? ".nii.gz" : ".nii";
  return writeThroughTemporaryPath(path, suffix, [&](const std::filesystem::path& temp) -> Result<void> {
    nim->nifti_type = NIFTI_FTYPE_NIFTI1_1;
    if (nifti_set_filenames(nim.get(), temp.c_str(), 0, 1) != 0)
      return makeError(Errc::Io, "cannot write '" + path.string() + "': the NIfTI library refused the file name");
    nifti_image_write(nim.get());
    if (!readsBackAs(temp, *nim))
      return makeError(Errc::Io,
                       "cannot write '" + path.string() + "': the file written does not read back (disk full or not writable?)");
    return {};
  });
}

Result<void> writeItkSnapLabels(const std::filesystem::path& path, const std::vector<LabelEntry>& table) {
  std::ostringstream t;
  t << "################################################\n"
       "# ITK-SnAP Label Description File\n"
       "# written by scansurf "
    << SCANSURF_VERSION_STRING
    << ": label = feature index + 1, 0 = background\n"
       "# File format:\n"
       "# IDX   -R-  -G-  -B-  -A--  VIS MSH  LABEL\n"
       "# Fields:\n"
       "#    IDX:   Zero-based index\n"
       "#    -R-:   Red color component (0..255)\n"
       "#    -G-:   Green color component (0..255)\n"
       "#    -B-:   Blue color component (0..255)\n"
       "#    -A-:   Label transparency (0.00 .. 1.00)\n"
       "#    VIS:   Label visibility (0 or 1)\n"
       "#    MSH:   Label mesh visibility (0 or 1)\n"
       "#  LABEL:   Label description\n"
       "################################################\n";
  char line[64];
  std::snprintf(line, sizeof line, "%5d %5d %4d %4d %8d %2d %2d    ", 0, 0, 0, 0, 0, 0, 0);
  t << line << "\"Clear Label\"\n";
  for (const LabelEntry& e : table) {
    std::string name = e.name;
    std::replace(name.begin(), name.end(), '"', '\'');  // the field is quoted
    name = oneLineText(name);
    std::snprintf(line, sizeof line, "%5d %5d %4d %4d %8d %2d %2d    ", int{e.label}, int{e.color[0]}, int{e.color[1]},
                  int{e.color[2]}, 1, 1, 1);
    t << line << '"' << name << "\"\n";
  }
  const std::string text = t.str();
  return writeFileAtomically(path, text.data(), text.size());
}

std::filesystem::path itkSnapLabelPathFor(const std::filesystem::path& niftiPath) {
  std::string name = niftiPath.filename().string();
  for (const char* ext : {".nii.gz", ".nii"})
    if (endsWith(name, ext)) {
      name.resize(name.size() - std::strlen(ext));
      break;
    }
  return niftiPath.parent_path() / (name + ".label.txt");
}

}  // namespace scansurf
