// scansurf: DICOM nesting depth without recursion. Element encoding after DICOM PS3.5 §7.1
// (data elements, explicit and implicit VR), §7.5 (nesting of data sets: items and
// delimitation items) and §A.5 (deflated explicit VR little endian).
#include "io/dicom_nesting.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdicent.h>
#include <dcmtk/dcmdata/dcdict.h>
#include <zlib.h>

#include <array>
#include <cstdint>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "core/memory.h"

namespace scansurf {
namespace {

constexpr std::uint32_t kUndefinedLength = 0xffffffffu;
constexpr std::uint64_t kOpenEnded = std::numeric_limits<std::uint64_t>::max();

enum class Syntax { ImplicitLittle, ExplicitLittle, ExplicitBig, DeflatedLittle };

struct Tag {
  std::uint16_t group = 0, element = 0;
};

// An open sequence or item: where its defined length ends (kOpenEnded until a delimiter).
struct Open {
  bool sequence = false;
  std::uint64_t end = kOpenEnded;
};

// Reads through the stream's buffer and counts the position itself: tellg and seekg on a file
// stream are system calls that drop the buffer, which made a 70 000-ROI file take 40 s.
class Reader {
 public:
  Reader(std::istream& in, bool bigEndian) : in_(in), big_(bigEndian), position_(static_cast<std::uint64_t>(in.tellg())) {}
  bool u16(std::uint16_t& v) {
    unsigned char b[2];
    if (!chars(reinterpret_cast<char*>(b), 2)) return false;
    v = big_ ? static_cast<std::uint16_t>(b[0] << 8 | b[1]) : static_cast<std::uint16_t>(b[1] << 8 | b[0]);
    return true;
  }
  bool u32(std::uint32_t& v) {
    std::uint16_t a, b;
    if (!u16(a) || !u16(b)) return false;
    v = big_ ? (std::uint32_t(a) << 16 | b) : (std::uint32_t(b) << 16 | a);
    return true;
  }
  bool chars(char* out, std::size_t n) {
    if (!in_.read(out, static_cast<std::streamsize>(n))) return false;
    position_ += n;
    return true;
  }
  std::uint64_t position() const { return position_; }
  bool skip(std::uint64_t n) {
    if (n <= (std::uint64_t{1} << 20)) {
      in_.ignore(static_cast<std::streamsize>(n));  // through the buffer
      if (static_cast<std::uint64_t>(in_.gcount()) != n) return false;
    } else {
      in_.seekg(static_cast<std::streamoff>(n), std::ios::cur);
      if (!in_) return false;
    }
    position_ += n;
    return !atEnd();
  }
  bool atEnd() { return in_.peek() == std::char_traits<char>::eof(); }

 private:
  std::istream& in_;
  bool big_;
  std::uint64_t position_;
};

bool hasLongLength(const char vr[2]) {
  static constexpr std::array<const char*, 13> kLong{"OB", "OD", "OF", "OL", "OV", "OW", "SQ",
                                                     "SV", "UC", "UN", "UR", "UT", "UV"};
  for (const char* v : kLong)
    if (vr[0] == v[0] && vr[1] == v[1]) return true;
  return false;
}

bool dictionarySaysSequence(Tag tag) {
  const DcmDataDictionary& dictionary = dcmDataDict.rdlock();
  const DcmDictEntry* entry = dictionary.findEntry(DcmTagKey(tag.group, tag.element), nullptr);
  const bool sequence = entry && entry->getEVR() == EVR_SQ;
  dcmDataDict.rdunlock();
  return sequence;
}

// Walks the data set's elements; returns the deepest sequence nesting seen (stopping as soon
// as it passes maxDepth).
int deepestNesting(Reader& in, Syntax syntax, bool stopAtPixelData, int maxDepth) {
  std::vector<Open> open;
  int depth = 0, deepest = 0;
  auto closeTo = [&](bool sequence) {  // a delimiter closes the innermost open-ended one of its kind
    while (!open.empty()) {
      const Open o = open.back();
      open.pop_back();
      depth -= o.sequence ? 1 : 0;
      if (o.sequence == sequence && o.end == kOpenEnded) return;
    }
  };
  while (!in.atEnd() && deepest <= maxDepth) {
    const std::uint64_t at = in.position();
    while (!open.empty() && open.back().end <= at) depth -= open.back().sequence ? 1 : 0, open.pop_back();
    Tag tag;
    std::uint32_t length = 0;
    if (!in.u16(tag.group) || !in.u16(tag.element)) break;
    if (tag.group == 0xfffe) {  // item, item delimiter, sequence delimiter: no VR, 32-bit length
      if (!in.u32(length)) break;
      if (tag.element == 0xe000)
        open.push_back({false, length == kUndefinedLength ? kOpenEnded : in.position() + length});
      else
        closeTo(tag.element == 0xe0dd);
      continue;
    }
    char vr[2] = {0, 0};
    bool sequence = false;
    if (syntax == Syntax::ImplicitLittle) {
      if (!in.u32(length)) break;
      sequence = length == kUndefinedLength || dictionarySaysSequence(tag);
    } else {
      std::uint16_t shortLength = 0;
      if (!in.chars(vr, 2)) break;
      if (hasLongLength(vr)) {
        if (!in.u16(shortLength) || !in.u32(length)) break;
      } else {
        if (!in.u16(shortLength)) break;
        length = shortLength;
      }
      // An undefined length marks a sequence (SQ, or UN holding one) or encapsulated pixel data.
      sequence = (vr[0] == 'S' && vr[1] == 'Q') || length == kUndefinedLength;
    }
    if (stopAtPixelData && depth == 0 && tag.group == 0x7fe0 && tag.element == 0x0010) break;
    if (sequence) {
      open.push_back({true, length == kUndefinedLength ? kOpenEnded : in.position() + length});
      deepest = std::max(deepest, ++depth);
    } else if (!in.skip(length)) {
      break;
    }
  }
  return deepest;
}

// Part 10 meta information (explicit VR little endian, group 0002): the Transfer Syntax UID.
std::string transferSyntaxOfMeta(Reader& in, std::istream& stream) {
  std::string syntax;
  while (true) {
    const std::streampos start = stream.tellg();
    std::uint16_t group = 0, element = 0, shortLength = 0;
    std::uint32_t length = 0;
    char vr[2];
    if (!in.u16(group) || group != 0x0002) {
      stream.clear();
      stream.seekg(start);
      return syntax;
    }
    if (!in.u16(element) || !in.chars(vr, 2)) return syntax;
    if (hasLongLength(vr)) {
      if (!in.u16(shortLength) || !in.u32(length)) return syntax;
    } else if (in.u16(shortLength)) {
      length = shortLength;
    } else {
      return syntax;
    }
    if (element == 0x0010 && length < 256) {
      syntax.assign(length, '\0');
      if (!in.chars(syntax.data(), length)) return syntax;
      while (!syntax.empty() && (syntax.back() == '\0' || syntax.back() == ' ')) syntax.pop_back();
    } else if (!in.skip(length)) {
      return syntax;
    }
  }
}

Syntax syntaxFromUid(const std::string& uid) {
  if (uid == "1.2.840.10008.1.2") return Syntax::ImplicitLittle;
  if (uid == "1.2.840.10008.1.2.2") return Syntax::ExplicitBig;
  if (uid == "1.2.840.10008.1.2.1.99") return Syntax::DeflatedLittle;
  return Syntax::ExplicitLittle;  // explicit VR little endian and every compressed syntax
}

// A bare data set (no Part 10 header): explicit when bytes 4-5 look like a VR; big endian when
// the first group reads as a byte-swapped small one.
Syntax guessSyntax(std::istream& stream) {
  unsigned char b[6] = {};
  const std::streampos start = stream.tellg();
  stream.read(reinterpret_cast<char*>(b), 6);
  stream.clear();
  stream.seekg(start);
  const bool explicitVr = b[4] >= 'A' && b[4] <= 'Z' && b[5] >= 'A' && b[5] <= 'Z';
  const bool big = b[0] == 0 && b[1] != 0;
  if (!explicitVr) return Syntax::ImplicitLittle;
  return big ? Syntax::ExplicitBig : Syntax::ExplicitLittle;
}

// The rest of the stream, inflated (raw deflate, RFC 1951); empty when it is not. Stops with
// `over` set once more than `limit` bytes came out: a 2 MB deflated file of zeros inflated to
// 4.1 GB and ended in an out-of-memory exit.
std::string inflateRest(std::istream& stream, std::uint64_t limit, bool& over) {
  std::string compressed((std::istreambuf_iterator<char>(stream)), {});
  std::string out;
  z_stream z{};
  if (inflateInit2(&z, -MAX_WBITS) != Z_OK) return out;
  z.next_in = reinterpret_cast<Bytef*>(compressed.data());
  z.avail_in = static_cast<uInt>(std::min<std::size_t>(compressed.size(), std::numeric_limits<uInt>::max()));
  std::array<char, 65536> chunk;
  int status = Z_OK;
  while (status == Z_OK) {
    z.next_out = reinterpret_cast<Bytef*>(chunk.data());
    z.avail_out = chunk.size();
    status = inflate(&z, Z_NO_FLUSH);
    out.append(chunk.data(), chunk.size() - z.avail_out);
    if (limit > 0 && out.size() > limit) {
      over = true;
      break;
    }
  }
  inflateEnd(&z);
  return out;
}

}  // namespace

Result<void> checkDicomNesting(const std::filesystem::path& path, bool stopAtPixelData, int maxDepth,
                               std::uint64_t inflateLimit) {
  std::ifstream stream(path, std::ios::binary);
  if (!stream) return {};  // the loader reports what it cannot open
  char preamble[132] = {};
  const bool part10 = stream.read(preamble, 132) && std::string_view(preamble + 128, 4) == "DICM";
  Syntax syntax;
  if (part10) {
    Reader meta(stream, false);
    syntax = syntaxFromUid(transferSyntaxOfMeta(meta, stream));
  } else {
    stream.clear();
    stream.seekg(0);
    syntax = guessSyntax(stream);
  }
  int deepest = 0;
  if (syntax == Syntax::DeflatedLittle) {
    // The parser holds the data set a few times over, as for a file of that size (checkInputFile).
    const HostMemory memory = inflateLimit > 0 ? HostMemory{} : availableHostMemory();
    const std::uint64_t limit = inflateLimit > 0 ? inflateLimit : memory.bytes / 4;
    bool over = false;
    std::istringstream inflated(inflateRest(stream, limit, over));
    if (over)
      return makeError(Errc::ResourceLimit, path.string() + ": its deflated data set inflates to more than " +
                                                formatBytes(limit) +
                                                (inflateLimit > 0 ? std::string(", the limit asked for")
                                                                  : ", a quarter of the " + formatBytes(memory.bytes) +
                                                                        " of memory available (" + memory.source + ")") +
                                                "; not read");
    Reader in(inflated, false);
    deepest = deepestNesting(in, Syntax::ExplicitLittle, stopAtPixelData, maxDepth);
  } else {
    Reader in(stream, syntax == Syntax::ExplicitBig);
    deepest = deepestNesting(in, syntax, stopAtPixelData, maxDepth);
  }
  if (deepest > maxDepth)
    return makeError(Errc::InvalidInput, path.string() + ": DICOM sequences nested more than " + std::to_string(maxDepth) +
                                             " deep (real objects nest fewer than 10); not read");
  return {};
}

}  // namespace scansurf
