// scansurf: IMOD binary model input (bio3d.colorado.edu/imod/doc/binspec.html, "IMOD Binary
// File Format, Version 1, Revision 2"): the layout is summarized in imod_reader.h.
#include "io/imod_reader.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>

#include "geometry/contours/validate.h"
#include "io/atomic_file.h"
#include "io/object_features.h"
#include "io/rtstruct_reader.h"

namespace scansurf {

namespace fs = std::filesystem;

namespace {

constexpr std::size_t kModelHeaderBytes = 232;
constexpr std::size_t kObjectBytes = 176;
constexpr std::size_t kContourHeaderBytes = 16;
constexpr std::size_t kMeshHeaderBytes = 16;
constexpr std::uint32_t kObjectOpen = 1u << 3;       // contours are not closed
constexpr std::uint32_t kObjectScattered = 1u << 9;  // contours are scattered points
constexpr std::uint32_t kContourOpen = 1u << 3;      // open contour in a closed object

Unexpected invalid(std::string message) { return makeError(Errc::InvalidInput, std::move(message)); }

// Big-endian fields of the file in memory; every read checked against its end.
class Bytes {
 public:
  Bytes(const std::string& data, const std::string& file) : data_(data), file_(file) {}
  std::size_t offset() const { return offset_; }
  std::size_t size() const { return data_.size(); }
  // An error unless n more bytes are there; `what` says what they would be.
  Result<void> need(std::uint64_t n, const std::string& what) const {
    if (n <= data_.size() - offset_) return {};
    return invalid(file_ + ": truncated: " + what + " needs " + std::to_string(n) + " bytes at offset " +
                   std::to_string(offset_) + ", but the file ends at " + std::to_string(data_.size()));
  }
  std::uint32_t u32() {
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(data_[offset_++]);
    return v;
  }
  std::int32_t i32() { return static_cast<std::int32_t>(u32()); }
  float f32() { return std::bit_cast<float>(u32()); }
  std::string text(std::size_t n) {
    std::string s = data_.substr(offset_, n);
    offset_ += n;
    s.resize(std::strlen(s.c_str()));  // null-terminated within its field
    while (!s.empty() && (s.back() == ' ' || s.back() == '\n' || s.back() == '\r' || s.back() == '\t')) s.pop_back();
    return s;
  }
  std::string id() { return text(4); }
  void skip(std::uint64_t n) { offset_ += static_cast<std::size_t>(n); }

 private:
  const std::string& data_;
  const std::string& file_;
  std::size_t offset_ = 0;
};

struct RawPoint {
  float x, y, z;
};

struct ModelContour {
  std::uint32_t flags = 0;
  std::vector<RawPoint> points;
};

struct ModelObject {
  RawObject raw;
  std::uint32_t flags = 0;
  int declaredContours = 0;
  std::vector<ModelContour> contours;
};

// "object 3 \"mito\"" (messages add the file in front).
std::string objectLabel(int number, const std::string& name) {
  std::string label = "object " + std::to_string(number);
  if (!name.empty()) label += " \"" + name + "\"";
  return label;
}

// A float field as written (0.01, not 0.009999999776482582).
std::string formatFloat(float value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::optional<Rgb> colorOf(float r, float g, float b) {
  const float c[3] = {r, g, b};
  Rgb rgb{};
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(c[i])) return std::nullopt;
    rgb[i] = static_cast<std::uint8_t>(std::lround(std::clamp(c[i], 0.0f, 1.0f) * 255));
  }
  return rgb;
}

std::string fieldsOf(float x, float y, float z) {
  std::string text = "(";
  text += formatFloat(x) + ", " + formatFloat(y) + ", " + formatFloat(z) + ")";
  return text;
}

// The file id and the model header (pixel size, scale, units); returns the object count.
Result<std::int32_t> readModelHeader(Bytes& in, const std::string& file, ImodModel& model) {
  SCANSURF_TRY(in.need(8, "the file id (IMOD and the version)"));
  if (in.id() != "IMOD") return invalid(file + ": not an IMOD model (it does not start with \"IMOD\")");
  const std::string version = in.id();
  if (version != "V1.2")
    return invalid(file + ": IMOD model version \"" + version + "\" (only the binary format V1.2 is supported)");
  SCANSURF_TRY(in.need(kModelHeaderBytes, "the model header"));
  model.name = in.text(128);
  in.skip(12);  // xmax, ymax, zmax
  const std::int32_t objectCount = in.i32();
  in.skip(4 * 5 + 4 * 3);  // flags, drawmode, mousemode, blacklevel, whitelevel; offsets
  for (double& s : model.scale) s = in.f32();
  in.skip(4 * 5);  // object, contour, point, res, thresh
  model.pixelSize = in.f32();
  model.unitsCode = in.i32();
  in.skip(4 * 4);  // csum, alpha, beta, gamma
  if (objectCount < 0) return invalid(file + ": the model header gives " + std::to_string(objectCount) + " objects");
  if (!(model.pixelSize > 0) || !std::isfinite(model.pixelSize))
    return invalid(file + ": pixel size " + formatFloat(static_cast<float>(model.pixelSize)) +
                   " in the model header (it must be positive)");
  const char* axes = "xyz";
  for (int a = 0; a < 3; ++a)
    if (!(model.scale[a] > 0) || !std::isfinite(model.scale[a]))
      return invalid(file + ": " + axes[a] + "scale " + formatFloat(static_cast<float>(model.scale[a])) +
                     " in the model header (it must be positive)");
  return objectCount;
}

Result<ModelObject> readObjectChunk(Bytes& in, const std::string& file, int number) {
  ModelObject object;
  object.raw.info.number = number;
  SCANSURF_TRY(in.need(kObjectBytes, objectLabel(number, "") + ": the OBJT chunk"));
  object.raw.info.name = in.text(64);
  in.skip(64);  // extra
  object.declaredContours = in.i32();
  object.flags = in.u32();
  in.skip(8);  // axis, drawmode
  const float r = in.f32(), g = in.f32(), b = in.f32();
  object.raw.info.color = colorOf(r, g, b);
  in.skip(4 + 8 + 8);  // pdrawsize; symbol .. trans; meshsize, surfsize
  if (object.declaredContours < 0)
    return invalid(file + ": " + objectLabel(number, object.raw.info.name) + ": " + std::to_string(object.declaredContours) +
                   " contours in its OBJT chunk");
  return object;
}

Result<ModelContour> readContourChunk(Bytes& in, const std::string& file, const std::string& where) {
  SCANSURF_TRY(in.need(kContourHeaderBytes, where + ": the CONT chunk"));
  const std::int32_t count = in.i32();
  ModelContour contour;
  contour.flags = in.u32();
  in.skip(8);  // time, surf
  if (count < 0) return invalid(file + ": " + where + ": " + std::to_string(count) + " points");
  SCANSURF_TRY(in.need(12ull * static_cast<std::uint64_t>(count), where + ": " + std::to_string(count) + " points"));
  contour.points.resize(static_cast<std::size_t>(count));
  for (RawPoint& p : contour.points) p.x = in.f32(), p.y = in.f32(), p.z = in.f32();
  return contour;
}

// A MESH chunk (IMOD's own surface) is passed over: scansurf makes its own.
Result<void> skipMeshChunk(Bytes& in, const std::string& file, const std::string& current, std::size_t chunkAt) {
  SCANSURF_TRY(in.need(kMeshHeaderBytes, current + ": the MESH chunk"));
  const std::int32_t vertices = in.i32(), indices = in.i32();
  in.skip(8);  // flag, time, surf
  if (vertices < 0 || indices < 0)
    return invalid(file + ": " + current + ": a MESH chunk at offset " + std::to_string(chunkAt) + " with " +
                   std::to_string(vertices) + " vertices and " + std::to_string(indices) + " indices");
  const std::uint64_t bytes = 12ull * static_cast<std::uint64_t>(vertices) + 4ull * static_cast<std::uint64_t>(indices);
  SCANSURF_TRY(in.need(bytes, current + ": the MESH chunk's data"));
  in.skip(bytes);
  return {};
}

// Every other chunk (IMAT, VIEW, MINX, SIZE, LABL, CLIP, stored values, ...) has its size.
Result<void> skipSizedChunk(Bytes& in, const std::string& file, const std::string& current, const std::string& id,
                            std::size_t chunkAt) {
  SCANSURF_TRY(in.need(4, current + ": the size of chunk \"" + id + "\""));
  const std::int32_t bytes = in.i32();
  if (bytes < 0)
    return invalid(file + ": " + current + ": chunk \"" + id + "\" at offset " + std::to_string(chunkAt) + " has size " +
                   std::to_string(bytes));
  SCANSURF_TRY(in.need(static_cast<std::uint64_t>(bytes), current + ": chunk \"" + id + "\""));
  in.skip(static_cast<std::uint64_t>(bytes));
  return {};
}

// The chunks up to IEOF: objects with their contours; the counts the headers declare checked.
Result<std::vector<ModelObject>> readChunks(Bytes& in, const std::string& file, std::int32_t objectCount) {
  std::vector<ModelObject> objects;
  for (;;) {
    if (in.offset() == in.size())
      return invalid(file + ": truncated: the file ends at " + std::to_string(in.size()) + " bytes without the IEOF end marker" +
                     (static_cast<std::int64_t>(objects.size()) < objectCount
                          ? " (" + std::to_string(objects.size()) + " of " + std::to_string(objectCount) + " objects read)"
                          : std::string()));
    SCANSURF_TRY(in.need(4, "a chunk id"));
    const std::size_t chunkAt = in.offset();
    const std::string id = in.id();
    // Where we are, for messages (the file in front is added by them).
    const std::string current =
        objects.empty() ? std::string("model") : objectLabel(static_cast<int>(objects.size()), objects.back().raw.info.name);
    if (id == "IEOF") break;
    if (id == "OBJT") {
      SCANSURF_ASSIGN_OR_RETURN(ModelObject object, readObjectChunk(in, file, static_cast<int>(objects.size()) + 1));
      objects.push_back(std::move(object));
    } else if (id == "CONT") {
      if (objects.empty()) return invalid(file + ": a CONT chunk at offset " + std::to_string(chunkAt) + " before any OBJT");
      ModelObject& object = objects.back();
      SCANSURF_ASSIGN_OR_RETURN(ModelContour contour,
                                readContourChunk(in, file, current + ", contour " + std::to_string(object.contours.size() + 1)));
      object.contours.push_back(std::move(contour));
    } else if (id == "MESH") {
      SCANSURF_TRY(skipMeshChunk(in, file, current, chunkAt));
    } else {
      SCANSURF_TRY(skipSizedChunk(in, file, current, id, chunkAt));
    }
  }
  if (static_cast<std::int64_t>(objects.size()) != objectCount)
    return invalid(file + ": the model header gives " + std::to_string(objectCount) + " objects, the file holds " +
                   std::to_string(objects.size()));
  for (const ModelObject& object : objects)
    if (static_cast<std::size_t>(object.declaredContours) != object.contours.size())
      return invalid(file + ": " + objectLabel(object.raw.info.number, object.raw.info.name) + ": its OBJT chunk gives " +
                     std::to_string(object.declaredContours) + " contours, the file holds " +
                     std::to_string(object.contours.size()));
  return objects;
}

// Unnamed objects are "object N"; repeated names made unique before selection.
void nameObjects(std::vector<ModelObject>& objects, const std::string& file, std::vector<std::string>& warnings) {
  for (ModelObject& object : objects)
    if (object.raw.info.name.empty()) object.raw.info.name = "object " + std::to_string(object.raw.info.number);
  std::vector<RawObject> named;
  for (ModelObject& object : objects) named.push_back(object.raw);
  makeObjectNamesUnique(named, file, warnings);
  for (std::size_t i = 0; i < objects.size(); ++i) objects[i].raw.info.name = named[i].info.name;
}

// The z range of a contour's points (image sections), or an error naming a non-finite point.
Result<std::pair<float, float>> zRangeOf(const ModelContour& contour, const std::string& where) {
  float zMin = 0, zMax = 0;
  for (std::size_t p = 0; p < contour.points.size(); ++p) {
    const RawPoint& q = contour.points[p];
    if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
      return invalid(where + ", point " + std::to_string(p + 1) + ": non-finite coordinate " + fieldsOf(q.x, q.y, q.z));
    zMin = p == 0 ? q.z : std::min(zMin, q.z);
    zMax = p == 0 ? q.z : std::max(zMax, q.z);
  }
  return std::pair{zMin, zMax};
}

// Where each closed contour's plane is: its object and its index in the object's closed list.
struct PlaneOwner {
  std::size_t object = 0, contour = 0;
};

// One closed object's closed, planar contours into object.raw.closed (in-plane scaled, z still
// in image sections); open and non-planar ones are counted and said.
Result<void> collectObjectContours(std::size_t o, ModelObject& object, ImodModel& model, const ImodOptions& options,
                                   std::vector<double>& planeZ, std::vector<PlaneOwner>& owners) {
  ObjectInfo& info = object.raw.info;
  const std::string who = model.contours.source + ": " + objectLabel(info.number, info.name);
  const bool selected = objectSelected(options.objectPatterns, info.name);
  const double sx = model.scale[0] * model.pixelSize, sy = model.scale[1] * model.pixelSize;
  int open = 0, nonPlanar = 0;
  for (std::size_t c = 0; c < object.contours.size(); ++c) {
    const ModelContour& contour = object.contours[c];
    if (contour.flags & kContourOpen) {
      ++open;
      continue;
    }
    const std::string where = who + ", contour " + std::to_string(c + 1);
    SCANSURF_ASSIGN_OR_RETURN(const auto range, zRangeOf(contour, where));
    if (range.second - range.first > options.planeTolerance) {
      const std::string why = where + ": not planar: its points span z " + formatFloat(range.first) + " .. " +
                              formatFloat(range.second) + " (image sections); only contours in one z plane are surfaced";
      if (selected && options.requireFeatures) return invalid(why);
      ++nonPlanar;
      if (selected) model.contours.warnings.push_back(why + "; skipped");
      continue;
    }
    ObjectContour closed;
    closed.z = contour.points.empty() ? 0.0 : contour.points.front().z;
    closed.points.reserve(contour.points.size());
    for (const RawPoint& q : contour.points) closed.points.push_back({q.x * sx, q.y * sy});
    planeZ.push_back(closed.z);
    owners.push_back({o, object.raw.closed.size()});
    object.raw.closed.push_back(std::move(closed));
  }
  info.skipped = open + nonPlanar;
  if (open > 0)
    model.contours.warnings.push_back(who + ": skipped " + std::to_string(open) +
                                      " open contour(s); only closed contours are surfaced");
  return {};
}

// Closed contours of closed objects; planes grouped by z in image sections, then scaled.
Result<std::vector<RawObject>> closedContours(std::vector<ModelObject>& objects, ImodModel& model, const ImodOptions& options) {
  std::vector<double> planeZ;
  std::vector<PlaneOwner> owners;
  for (std::size_t o = 0; o < objects.size(); ++o) {
    ModelObject& object = objects[o];
    if (object.flags & (kObjectOpen | kObjectScattered)) {
      object.raw.info.skipped = static_cast<int>(object.contours.size());
      model.contours.warnings.push_back(model.contours.source + ": " + objectLabel(object.raw.info.number, object.raw.info.name) +
                                        ": " + ((object.flags & kObjectScattered) ? "scattered points" : "an open object") +
                                        ", skipped (" + std::to_string(object.contours.size()) +
                                        " contours); only closed objects are surfaced");
      continue;
    }
    SCANSURF_TRY(collectObjectContours(o, object, model, options, planeZ, owners));
  }
  const double sz = model.scale[2] * model.pixelSize;
  const std::vector<double> planes = groupSlicePlanes(planeZ, options.planeTolerance);
  for (std::size_t i = 0; i < planes.size(); ++i) objects[owners[i].object].raw.closed[owners[i].contour].z = planes[i] * sz;
  std::vector<RawObject> raws;
  for (ModelObject& object : objects) raws.push_back(std::move(object.raw));
  return raws;
}

std::string modelNote(const ImodModel& model) {
  int surfaced = 0;
  for (const ObjectInfo& o : model.objects) surfaced += o.feature >= 0;
  return "IMOD model \"" + model.name + "\": " + std::to_string(model.objects.size()) + " objects, " + std::to_string(surfaced) +
         " surfaced; pixel size " + formatFloat(static_cast<float>(model.pixelSize)) + " " + model.contours.units + ", scale (" +
         formatFloat(static_cast<float>(model.scale[0])) + ", " + formatFloat(static_cast<float>(model.scale[1])) + ", " +
         formatFloat(static_cast<float>(model.scale[2])) + "); coordinates in " + model.contours.units;
}

}  // namespace

std::string imodUnitName(int code) {
  switch (code) {
    case 0: return "pixels";
    case 3: return "km";
    case 1: return "m";
    case -2: return "cm";
    case -3: return "mm";
    case -6: return "\xC2\xB5m";  // µm
    case -9: return "nm";
    case -10: return "\xC3\x85";  // Å
    case -12: return "pm";
    default: return {};
  }
}

bool hasImodMagic(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  char id[4];
  return in.read(id, 4) && std::memcmp(id, "IMOD", 4) == 0;
}

Result<ImodModel> readImodModel(const fs::path& path, const ImodOptions& options) {
  const std::string file = path.string();
  SCANSURF_ASSIGN_OR_RETURN(const std::string data, readWholeFile(path));
  Bytes in(data, file);
  ImodModel model;
  model.contours.source = file;
  SCANSURF_ASSIGN_OR_RETURN(const std::int32_t objectCount, readModelHeader(in, file, model));
  SCANSURF_ASSIGN_OR_RETURN(std::vector<ModelObject> objects, readChunks(in, file, objectCount));
  nameObjects(objects, file, model.contours.warnings);
  SCANSURF_ASSIGN_OR_RETURN(std::vector<RawObject> raws, closedContours(objects, model, options));
  const std::string unitName = imodUnitName(model.unitsCode);
  model.contours.units = unitName.empty() ? "units code " + std::to_string(model.unitsCode) : unitName;
  if (unitName.empty())
    model.contours.warnings.push_back(file + ": unknown units code " + std::to_string(model.unitsCode) +
                                      " in the model header; coordinates are pixel size x pixels");
  SCANSURF_ASSIGN_OR_RETURN(model.objects,
                            buildObjectFeatures(raws, {options.objectPatterns, options.requireFeatures}, model.contours));
  model.contours.notes.push_back(modelNote(model));
  return model;
}

}  // namespace scansurf
