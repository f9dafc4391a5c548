// scansurf: VTK XML data arrays (see vtk_xml_arrays.h).
#include "io/vtk_xml_arrays.h"

#include <openssl/evp.h>
#include <zlib.h>

#include <cctype>
#include <cstring>
#include <pugixml.hpp>
#include <sstream>

namespace scansurf {
namespace {

Unexpected bad(const std::string& where, const std::string& what) { return makeError(Errc::InvalidInput, where + ": " + what); }

// Base64 without whitespace into bytes, padding removed.
Result<std::string> fromBase64(const std::string& text, const std::string& where) {
  if (text.size() % 4 != 0) return bad(where, "base64 data whose length is not a multiple of 4");
  std::string out(text.size() / 4 * 3, '\0');
  const int n = EVP_DecodeBlock(reinterpret_cast<unsigned char*>(out.data()), reinterpret_cast<const unsigned char*>(text.data()),
                                static_cast<int>(text.size()));
  if (n < 0) return bad(where, "malformed base64 data");
  std::size_t padding = 0;
  while (padding < 2 && padding < text.size() && text[text.size() - 1 - padding] == '=') ++padding;
  out.resize(static_cast<std::size_t>(n) - padding);
  return out;
}

std::string withoutSpace(const char* text) {
  std::string out;
  for (const char* c = text; *c; ++c)
    if (!std::isspace(static_cast<unsigned char>(*c))) out += *c;
  return out;
}

// Word i of a header, little-endian whatever the host (the caller checked the size). Not
// inlined: GCC 12 then takes the SSO buffer of a filled string for uninitialized.
[[gnu::noinline]] std::uint64_t headerWord(const std::string& bytes, std::size_t i, bool wide) {
  const std::size_t width = wide ? 8 : 4;
  const auto* at = reinterpret_cast<const unsigned char*>(bytes.data()) + width * i;
  std::uint64_t v = 0;
  for (std::size_t b = 0; b < width; ++b) v |= static_cast<std::uint64_t>(at[b]) << (8 * b);
  return v;
}

std::size_t base64Length(std::size_t bytes) { return (bytes + 2) / 3 * 4; }

// Compressed binary: a header (blocks, block size, last block size, compressed sizes) in
// base64 of its own, then the compressed blocks together in base64.
Result<std::string> inflateBlocks(const std::string& text, bool wide, const std::string& where) {
  const std::size_t word = wide ? 8 : 4;
  SCANSURF_ASSIGN_OR_RETURN(const std::string first, fromBase64(text.substr(0, base64Length(3 * word)), where));
  if (first.size() < 3 * word) return bad(where, "compressed data without its header");
  const std::uint64_t blocks = headerWord(first, 0, wide), blockSize = headerWord(first, 1, wide);
  const std::uint64_t lastSize = headerWord(first, 2, wide);
  const std::size_t headerText = base64Length((3 + blocks) * word);
  if (blocks > text.size() || headerText > text.size() || blockSize > (std::uint64_t{1} << 30))
    return bad(where, "a compressed-data header larger than its data");
  SCANSURF_ASSIGN_OR_RETURN(const std::string header, fromBase64(text.substr(0, headerText), where));
  SCANSURF_ASSIGN_OR_RETURN(const std::string packed, fromBase64(text.substr(headerText), where));
  std::string out;
  std::size_t at = 0;
  for (std::uint64_t b = 0; b < blocks; ++b) {
    const std::uint64_t size = headerWord(header, 3 + b, wide);
    const std::uint64_t expected = b + 1 == blocks && lastSize != 0 ? lastSize : blockSize;
    if (size > packed.size() - at) return bad(where, "compressed blocks longer than the data");
    // A block inflates to at most about 1032 times its size (zlib's limit): refuse more.
    if (expected > 1100 * (size + 16)) return bad(where, "a compressed block that claims to inflate beyond zlib's ratio");
    std::string block(expected, '\0');
    uLongf length = static_cast<uLongf>(expected);
    if (uncompress(reinterpret_cast<Bytef*>(block.data()), &length, reinterpret_cast<const Bytef*>(packed.data() + at),
                   static_cast<uLong>(size)) != Z_OK ||
        length != expected)
      return bad(where, "a compressed block that does not inflate to its stated size");
    out += block;
    at += size;
  }
  return out;
}

// Uncompressed binary: the byte count, then the bytes, in one base64 text.
Result<std::string> plainBlock(const std::string& text, bool wide, const std::string& where) {
  SCANSURF_ASSIGN_OR_RETURN(std::string bytes, fromBase64(text, where));
  const std::size_t word = wide ? 8 : 4;
  if (bytes.size() < word) return bad(where, "binary data without its size");
  const std::uint64_t size = headerWord(bytes, 0, wide);
  if (size > bytes.size() - word) return bad(where, "binary data shorter than its stated size");
  return bytes.substr(word, static_cast<std::size_t>(size));
}

Result<std::string> binaryBytes(const pugi::xml_node& array, const VtkXmlEncoding& encoding, const std::string& where) {
  const std::string text = withoutSpace(array.text().get());
  return encoding.zlib ? inflateBlocks(text, encoding.uint64Header, where) : plainBlock(text, encoding.uint64Header, where);
}

template <typename T>
void append(const std::string& bytes, std::vector<double>& out) {
  const std::size_t n = bytes.size() / sizeof(T);
  for (std::size_t i = 0; i < n; ++i) {
    T v;
    std::memcpy(&v, bytes.data() + i * sizeof(T), sizeof(T));
    out.push_back(static_cast<double>(v));
  }
}

Result<std::vector<double>> numbersOf(const std::string& bytes, const std::string& type, const std::string& where) {
  std::vector<double> out;
  if (type == "Float32")
    append<float>(bytes, out);
  else if (type == "Float64")
    append<double>(bytes, out);
  else if (type == "Int8")
    append<std::int8_t>(bytes, out);
  else if (type == "UInt8")
    append<std::uint8_t>(bytes, out);
  else if (type == "Int16")
    append<std::int16_t>(bytes, out);
  else if (type == "UInt16")
    append<std::uint16_t>(bytes, out);
  else if (type == "Int32")
    append<std::int32_t>(bytes, out);
  else if (type == "UInt32")
    append<std::uint32_t>(bytes, out);
  else if (type == "Int64")
    append<std::int64_t>(bytes, out);
  else if (type == "UInt64")
    append<std::uint64_t>(bytes, out);
  else
    return bad(where, "an array of type \"" + type + "\", not a number type");
  return out;
}

}  // namespace

Result<VtkXmlEncoding> vtkXmlEncoding(const pugi::xml_node& vtkFile, const std::string& where) {
  VtkXmlEncoding e;
  const std::string order = vtkFile.attribute("byte_order").as_string("LittleEndian");
  if (order != "LittleEndian") return bad(where, "byte_order \"" + order + "\": only LittleEndian files are read");
  const std::string header = vtkFile.attribute("header_type").as_string("UInt32");
  if (header != "UInt32" && header != "UInt64") return bad(where, "header_type \"" + header + "\" (UInt32 or UInt64 expected)");
  e.uint64Header = header == "UInt64";
  const std::string compressor = vtkFile.attribute("compressor").as_string("");
  if (!compressor.empty() && compressor != "vtkZLibDataCompressor")
    return bad(where, "compressor \"" + compressor + "\": only vtkZLibDataCompressor (zlib) is read");
  e.zlib = !compressor.empty();
  return e;
}

Result<std::string> vtkBytes(const pugi::xml_node& array, const VtkXmlEncoding& encoding, const std::string& where) {
  const std::string format = array.attribute("format").as_string("ascii");
  if (format == "binary") return binaryBytes(array, encoding, where);
  if (format == "ascii") return std::string(array.text().get());
  return bad(where, "format \"" + format + "\": inline binary or ascii data is read, not appended data");
}

Result<std::vector<double>> vtkNumbers(const pugi::xml_node& array, const VtkXmlEncoding& encoding, const std::string& where) {
  const std::string type = array.attribute("type").as_string("");
  const std::string format = array.attribute("format").as_string("ascii");
  if (format == "ascii") {
    std::istringstream in(array.text().get());
    std::vector<double> out;
    for (double v; in >> v;) out.push_back(v);
    if (!in.eof()) return bad(where, "ascii data that is not a list of numbers");
    return out;
  }
  SCANSURF_ASSIGN_OR_RETURN(const std::string bytes, vtkBytes(array, encoding, where));
  return numbersOf(bytes, type, where);
}

}  // namespace scansurf
