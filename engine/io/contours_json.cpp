// scansurf: contour set JSON reader and writer.
#include "io/contours_json.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "geometry/contours/validate.h"
#include "io/atomic_file.h"

namespace scansurf {

namespace {

using Json = nlohmann::json;

Unexpected invalid(std::string message) { return makeError(Errc::InvalidInput, std::move(message)); }

// The format nests 8 deep (document, features, feature, slices, slice, contours, contour,
// point); anything far deeper is hostile and is refused while parsing, before a recursive
// walk (dump, destruction) could exhaust the stack.
constexpr int kMaxDepth = 64;
struct TooDeep {
  std::size_t depth;
};

// The parser's own message quotes the last token read, which may be megabytes long.
std::string shortened(std::string message) {
  if (message.size() > 200) message = message.substr(0, 197) + "...";
  return message;
}

// A value quoted in an error message, cut short: never a megabyte of JSON in a message.
std::string quoted(const Json& j) {
  std::string text = j.dump(-1, ' ', false, Json::error_handler_t::replace);
  if (text.size() > 60) text = text.substr(0, 57) + "...";
  return text;
}

const char* typeName(const Json& j) { return j.type_name(); }

// Where in the file a structural error is: builds the prefix as far as it is known.
struct Location {
  const std::string* source = nullptr;
  int feature = -1;
  std::string featureName;
  bool haveName = false;
  int slice = -1;
  double z = 0;
  bool haveZ = false;
  int contour = -1;
  int point = -1;

  std::string text() const {
    std::string s = *source;
    if (feature >= 0) {
      s += haveName ? ": feature \"" + featureName + "\" (#" + std::to_string(feature) + ")"
                    : ": feature #" + std::to_string(feature);
    }
    if (slice >= 0) {
      s += haveZ ? ", slice z=" + formatNumber(z) + " (#" + std::to_string(slice) + ")" : ", slice #" + std::to_string(slice);
    }
    if (contour >= 0) s += ", contour " + std::to_string(contour);
    if (point >= 0) s += ", point " + std::to_string(point);
    return s;
  }
};

Result<Rgb> parseColor(const Json& j, const Location& at) {
  if (!j.is_array() || j.size() != 3) return invalid(at.text() + ": \"color\" must be an array of 3 integers in 0..255");
  Rgb rgb{};
  for (std::size_t i = 0; i < 3; ++i) {
    const Json& c = j[i];
    if (!c.is_number_integer())
      return invalid(at.text() + ": \"color\" must be an array of 3 integers in 0..255, component " + std::to_string(i) + " is " +
                     quoted(c));
    const std::int64_t v = c.is_number_unsigned()
                               ? static_cast<std::int64_t>(std::min<std::uint64_t>(c.get<std::uint64_t>(), 1000))
                               : c.get<std::int64_t>();
    if (v < 0 || v > 255)
      return invalid(at.text() + ": \"color\" component " + std::to_string(i) + " is " + std::to_string(v) + ", outside 0..255");
    rgb[i] = static_cast<std::uint8_t>(v);
  }
  return rgb;
}

Result<Contour> parseContour(const Json& j, Location at) {
  if (!j.is_array()) return invalid(at.text() + ": a contour must be an array of points, found " + typeName(j));
  Contour contour;
  contour.points.reserve(j.size());
  for (std::size_t p = 0; p < j.size(); ++p) {
    const Json& point = j[p];
    if (!point.is_array() || point.size() != 2 || !point[0].is_number() || !point[1].is_number()) {
      at.point = static_cast<int>(p);
      return invalid(at.text() + ": a point must be an array of 2 numbers, found " + quoted(point));
    }
    contour.points.push_back(Point2{point[0].get<double>(), point[1].get<double>()});
  }
  return contour;
}

Result<FeatureSlice> parseSlice(const Json& j, Location at) {
  if (!j.is_object()) return invalid(at.text() + ": a slice must be an object, found " + typeName(j));
  FeatureSlice slice;
  const auto z = j.find("z");
  if (z == j.end()) return invalid(at.text() + ": missing \"z\"");
  if (!z->is_number()) return invalid(at.text() + ": \"z\" must be a number, found " + typeName(*z));
  slice.z = z->get<double>();
  at.z = slice.z;
  at.haveZ = true;
  const auto contours = j.find("contours");
  if (contours == j.end()) return invalid(at.text() + ": missing \"contours\"");
  if (!contours->is_array()) return invalid(at.text() + ": \"contours\" must be an array, found " + typeName(*contours));
  for (std::size_t c = 0; c < contours->size(); ++c) {
    at.contour = static_cast<int>(c);
    SCANSURF_ASSIGN_OR_RETURN(Contour contour, parseContour((*contours)[c], at));
    slice.contours.push_back(std::move(contour));
  }
  return slice;
}

Result<Feature> parseFeature(const Json& j, Location at) {
  if (!j.is_object()) return invalid(at.text() + ": a feature must be an object, found " + typeName(j));
  Feature feature;
  const auto name = j.find("name");
  if (name == j.end()) return invalid(at.text() + ": missing \"name\"");
  if (!name->is_string()) return invalid(at.text() + ": \"name\" must be a string, found " + typeName(*name));
  feature.name = name->get<std::string>();
  at.featureName = feature.name;
  at.haveName = true;
  if (const auto color = j.find("color"); color != j.end()) {
    SCANSURF_ASSIGN_OR_RETURN(feature.color, parseColor(*color, at));
  }
  const auto slices = j.find("slices");
  if (slices == j.end()) return invalid(at.text() + ": missing \"slices\"");
  if (!slices->is_array()) return invalid(at.text() + ": \"slices\" must be an array, found " + typeName(*slices));
  for (std::size_t s = 0; s < slices->size(); ++s) {
    at.slice = static_cast<int>(s);
    SCANSURF_ASSIGN_OR_RETURN(FeatureSlice slice, parseSlice((*slices)[s], at));
    feature.slices.push_back(std::move(slice));
  }
  return feature;
}

Result<ContourSet> parseDocument(const Json& root, std::string source) {
  ContourSet set;
  set.source = std::move(source);
  Location at;
  at.source = &set.source;
  if (!root.is_object()) return invalid(set.source + ": the document must be a JSON object, found " + typeName(root));

  const auto version = root.find("version");
  if (version == root.end()) return invalid(set.source + ": missing \"version\" (expected 1)");
  if (!version->is_number_integer() || version->get<std::int64_t>() != 1)
    return invalid(set.source + ": unsupported \"version\" " + quoted(*version) + " (expected 1)");

  if (const auto units = root.find("units"); units != root.end()) {
    if (!units->is_string()) return invalid(set.source + ": \"units\" must be a string, found " + typeName(*units));
    set.units = units->get<std::string>();
  }

  const auto features = root.find("features");
  if (features == root.end()) return invalid(set.source + ": missing \"features\"");
  if (!features->is_array()) return invalid(set.source + ": \"features\" must be an array, found " + typeName(*features));
  for (std::size_t f = 0; f < features->size(); ++f) {
    at.feature = static_cast<int>(f);
    SCANSURF_ASSIGN_OR_RETURN(Feature feature, parseFeature((*features)[f], at));
    set.features.push_back(std::move(feature));
  }

  if (const auto order = root.find("order"); order != root.end()) {
    if (!order->is_array()) return invalid(set.source + ": \"order\" must be an array of feature names");
    for (std::size_t i = 0; i < order->size(); ++i) {
      const Json& entry = (*order)[i];
      if (!entry.is_string())
        return invalid(set.source + ": \"order\" entry " + std::to_string(i) + " must be a feature name, found " + quoted(entry));
      const std::string name = entry.get<std::string>();
      int index = -1;
      for (std::size_t f = 0; f < set.features.size() && index < 0; ++f)
        if (set.features[f].name == name) index = static_cast<int>(f);
      if (index < 0)
        return invalid(set.source + ": \"order\" entry " + std::to_string(i) + " names unknown feature \"" + name + "\"");
      set.order.push_back(index);
    }
    // An explicit but empty order names no feature: let validation report the first one missing.
    if (order->empty() && !set.features.empty())
      return invalid(set.source + ": feature \"" + set.features[0].name + "\" (#0): missing from order");
  }

  SCANSURF_TRY(validateAndNormalize(set));
  return set;
}

}  // namespace

Result<ContourSet> parseContoursJson(std::string_view text, std::string source) {
  Json root;
  try {
    root = Json::parse(text.begin(), text.end(), [](int depth, Json::parse_event_t event, Json&) {
      if (depth > kMaxDepth && (event == Json::parse_event_t::object_start || event == Json::parse_event_t::array_start))
        throw TooDeep{static_cast<std::size_t>(depth)};
      return true;
    });
  } catch (const TooDeep&) {
    return invalid(source + ": values nested more than " + std::to_string(kMaxDepth) +
                   " deep (the contour format nests 8 deep): refused");
  } catch (const Json::parse_error& e) {
    return invalid(source + ": not valid JSON at byte " + std::to_string(e.byte) + ": " + shortened(e.what()));
  } catch (const Json::exception& e) {
    // e.g. a number too large for a double: nlohmann reports it without a position.
    return invalid(source + ": not valid JSON: " + shortened(e.what()));
  }
  try {
    return parseDocument(root, std::move(source));
  } catch (const Json::exception& e) {
    return invalid(source + ": " + e.what());  // a type check missed above; still bad input
  }
}

Result<ContourSet> readContoursJson(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return makeError(Errc::Io, "cannot open " + path.string() + " for reading");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) return makeError(Errc::Io, "cannot read " + path.string());
  return parseContoursJson(buffer.str(), path.string());
}

namespace {

std::string number(double v) { return Json(v).dump(); }
// A JSON string; bytes that are not UTF-8 (a Latin-1 name) become U+FFFD instead of throwing.
std::string text(const std::string& s) { return Json(s).dump(-1, ' ', false, Json::error_handler_t::replace); }

}  // namespace

std::string formatContoursJson(const ContourSet& contours) {
  // Hand-laid-out so the file stays readable and diffable: one line per contour.
  std::string out;
  out += "{\n  \"version\": 1,\n  \"units\": " + text(contours.units) + ",\n  \"features\": [";
  for (std::size_t f = 0; f < contours.features.size(); ++f) {
    const Feature& feature = contours.features[f];
    out += f ? ",\n" : "\n";
    out += "    {\n      \"name\": " + text(feature.name) + ",\n";
    if (feature.color) {
      const Rgb& c = *feature.color;
      out += "      \"color\": [" + std::to_string(c[0]) + ", " + std::to_string(c[1]) + ", " + std::to_string(c[2]) + "],\n";
    }
    out += "      \"slices\": [";
    for (std::size_t s = 0; s < feature.slices.size(); ++s) {
      const FeatureSlice& slice = feature.slices[s];
      out += s ? ",\n" : "\n";
      out += "        { \"z\": " + number(slice.z) + ", \"contours\": [";
      for (std::size_t c = 0; c < slice.contours.size(); ++c) {
        out += c ? ",\n            [" : "\n            [";
        const auto& pts = slice.contours[c].points;
        for (std::size_t p = 0; p < pts.size(); ++p) {
          if (p) out += ',';
          out += '[' + number(pts[p].x) + ',' + number(pts[p].y) + ']';
        }
        out += ']';
      }
      out += " ] }";
    }
    out += feature.slices.empty() ? "]\n    }" : "\n      ]\n    }";
  }
  out += contours.features.empty() ? "]" : "\n  ]";
  if (!contours.order.empty()) {
    out += ",\n  \"order\": [";
    for (std::size_t i = 0; i < contours.order.size(); ++i) {
      if (i) out += ", ";
      out += text(contours.features[contours.order[i]].name);
    }
    out += "]";
  }
  out += "\n}\n";
  return out;
}

Result<void> writeContoursJson(const ContourSet& contours, const std::filesystem::path& path) {
  // JSON cannot hold NaN or infinity: refuse rather than write null.
  const int featureCount = static_cast<int>(contours.features.size());
  for (int f = 0; f < featureCount; ++f)
    for (const FeatureSlice& slice : contours.features[f].slices) {
      bool finite = std::isfinite(slice.z);
      for (const Contour& c : slice.contours)
        for (const Point2& p : c.points) finite = finite && std::isfinite(p.x) && std::isfinite(p.y);
      if (!finite)
        return makeError(Errc::InvalidArgument,
                         describeFeature(contours, f) + ": non-finite value, cannot write " + path.string());
    }
  for (int f : contours.order)
    if (f < 0 || f >= featureCount)
      return makeError(Errc::InvalidArgument,
                       "order index " + std::to_string(f) + " out of range, cannot write " + path.string());

  const std::string text = formatContoursJson(contours);
  return writeFileAtomically(path, text.data(), text.size());
}

}  // namespace scansurf
