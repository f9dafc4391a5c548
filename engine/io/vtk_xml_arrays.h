// scansurf: the data arrays of VTK's XML files (the "VTK File Formats" section of the VTK
// User's Guide, kitware.com): inline "binary" data, base64 with a UInt32 or UInt64 header,
// optionally in zlib-compressed blocks (vtkZLibDataCompressor), and "ascii" data. Decoded
// with OpenSSL's base64 and zlib; sizes are checked against the text before anything large is
// allocated.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scansurf/result.h"

namespace pugi {
class xml_node;
}

namespace scansurf {

// How the file stores binary arrays (attributes of its VTKFile element).
struct VtkXmlEncoding {
  bool uint64Header = false;  // header_type="UInt64"
  bool zlib = false;          // compressor="vtkZLibDataCompressor"
};

// Reads the VTKFile element's encoding; refuses big-endian data and compressors other than zlib.
Result<VtkXmlEncoding> vtkXmlEncoding(const pugi::xml_node& vtkFile, const std::string& where);

// The array's values as doubles (any numeric type), or its bytes (type="String"): `where`
// names the file and array in errors.
Result<std::vector<double>> vtkNumbers(const pugi::xml_node& array, const VtkXmlEncoding& encoding, const std::string& where);
Result<std::string> vtkBytes(const pugi::xml_node& array, const VtkXmlEncoding& encoding, const std::string& where);

}  // namespace scansurf
