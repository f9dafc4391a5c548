// scansurf: Reconstruct series input (XML series and section files), read with pugixml.
// The format's facts (Transform dimensions, the inverse mapping of trace points, section
// depth) are those of Reconstruct 1.1 as documented in reconstruct_reader.h.
#include "io/reconstruct_reader.h"

#include <pugixml.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include "geometry/contours/validate.h"
#include "io/atomic_file.h"
#include "io/object_features.h"

namespace scansurf {

namespace fs = std::filesystem;

namespace {

Unexpected invalid(std::string message) { return makeError(Errc::InvalidInput, std::move(message)); }

bool isSeparator(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == ','; }

// Every number in text (white space and commas separate them); nullopt and the offending
// token in `bad` when one is not a number.
std::optional<std::vector<double>> parseNumbers(std::string_view text, std::string& bad) {
  std::vector<double> values;
  std::size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && isSeparator(text[i])) ++i;
    std::size_t end = i;
    while (end < text.size() && !isSeparator(text[end])) ++end;
    if (end == i) break;
    const std::string_view token = text.substr(i, end - i);
    double v = 0;
    const char* first = token.data() + (token.front() == '+' ? 1 : 0);
    const auto [ptr, ec] = std::from_chars(first, token.data() + token.size(), v);
    if (ec != std::errc() || ptr != token.data() + token.size() || !std::isfinite(v)) {
      bad = std::string(token);
      return std::nullopt;
    }
    values.push_back(v);
    i = end;
  }
  return values;
}

bool parseBool(const pugi::xml_attribute& attribute, bool fallback) {
  if (!attribute) return fallback;
  std::string v = attribute.value();
  std::transform(v.begin(), v.end(), v.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (v == "true" || v == "1" || v == "yes") return true;
  if (v == "false" || v == "0" || v == "no") return false;
  return fallback;
}

// A trace colour "r g b" (0..1 each); nullopt when absent or malformed (colour is cosmetic).
std::optional<Rgb> parseColor(const pugi::xml_attribute& attribute) {
  if (!attribute) return std::nullopt;
  std::string bad;
  const auto v = parseNumbers(attribute.value(), bad);
  if (!v || v->size() != 3) return std::nullopt;
  Rgb rgb{};
  for (int c = 0; c < 3; ++c) {
    if ((*v)[c] < 0 || (*v)[c] > 1) return std::nullopt;
    rgb[c] = static_cast<std::uint8_t>(std::lround((*v)[c] * 255));
  }
  return rgb;
}

// Parses an XML file; errors give the line and pugixml's description.
Result<void> loadXml(const fs::path& path, pugi::xml_document& doc) {
  SCANSURF_ASSIGN_OR_RETURN(const std::string text, readWholeFile(path));
  const pugi::xml_parse_result parsed = doc.load_buffer(text.data(), text.size());
  if (parsed) return {};
  const auto offset =
      static_cast<std::size_t>(std::clamp<std::ptrdiff_t>(parsed.offset, 0, static_cast<std::ptrdiff_t>(text.size())));
  const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(offset), '\n');
  return invalid(path.string() + ": malformed XML at line " + std::to_string(line) + ": " + parsed.description());
}

// A trace as read: section coordinates for closed traces.
struct Trace {
  std::string name;
  bool closed = true;
  std::optional<Rgb> color;
  std::vector<Point2> points;
};

struct Section {
  fs::path path;
  int index = 0;
  double thickness = 0;
  double z = 0;
  std::vector<Trace> traces;
};

Result<int> intAttribute(const pugi::xml_node& node, const char* name, const std::string& where) {
  const pugi::xml_attribute a = node.attribute(name);
  if (!a) return invalid(where + ": missing attribute " + name);
  const std::string_view v = a.value();
  int value = 0;
  const auto [ptr, ec] = std::from_chars(v.data(), v.data() + v.size(), value);
  if (ec != std::errc() || ptr != v.data() + v.size())
    return invalid(where + ": attribute " + name + "=\"" + std::string(v) + "\" is not an integer");
  return value;
}

Result<double> numberAttribute(const pugi::xml_node& node, const char* name, const std::string& where) {
  const pugi::xml_attribute a = node.attribute(name);
  if (!a) return invalid(where + ": missing attribute " + name);
  std::string bad;
  const auto v = parseNumbers(a.value(), bad);
  if (!v || v->size() != 1) return invalid(where + ": attribute " + name + "=\"" + a.value() + "\" is not a number");
  return v->front();
}

Result<ReconstructTransform> readTransform(const pugi::xml_node& node, const std::string& where) {
  SCANSURF_ASSIGN_OR_RETURN(const int dim, intAttribute(node, "dim", where));
  std::vector<double> coef[2];
  const char* names[2] = {"xcoef", "ycoef"};
  for (int k = 0; k < 2; ++k) {
    const pugi::xml_attribute a = node.attribute(names[k]);
    if (!a) {
      if (dim == 0) continue;
      return invalid(where + ": missing attribute " + names[k]);
    }
    std::string bad;
    auto v = parseNumbers(a.value(), bad);
    if (!v) return invalid(where + ": " + names[k] + " holds \"" + bad + "\", not a number");
    if (v->size() > 6) return invalid(where + ": " + names[k] + " holds " + std::to_string(v->size()) + " numbers, more than 6");
    coef[k] = std::move(*v);
  }
  auto t = ReconstructTransform::fromFile(dim, coef[0], coef[1]);
  if (!t) return invalid(where + ": " + t.error().message);
  return t;
}

// One section file, its closed traces mapped into section coordinates.
Result<Section> readSection(const fs::path& path) {
  pugi::xml_document doc;
  SCANSURF_TRY(loadXml(path, doc));
  const std::string file = path.string();
  const pugi::xml_node root = doc.document_element();
  if (std::string_view(root.name()) != "Section")
    return invalid(file + ": not a Reconstruct section file (root element <" + std::string(root.name()) +
                   ">, expected <Section>)");
  Section section;
  section.path = path;
  SCANSURF_ASSIGN_OR_RETURN(section.index, intAttribute(root, "index", file + ": <Section>"));
  if (section.index < 0) return invalid(file + ": section index " + std::to_string(section.index) + " is negative");
  const std::string where = file + ": section " + std::to_string(section.index);
  SCANSURF_ASSIGN_OR_RETURN(section.thickness, numberAttribute(root, "thickness", where));
  if (!(section.thickness > 0))
    return invalid(where + ": thickness " + formatNumber(section.thickness) + " (it must be positive)");

  int transformNumber = 0, traceNumber = 0;
  for (const pugi::xml_node& transformNode : root.children("Transform")) {
    ++transformNumber;
    const bool image = static_cast<bool>(transformNode.child("Image"));
    std::optional<ReconstructTransform> transform;
    for (const pugi::xml_node& contour : transformNode.children("Contour")) {
      if (image) continue;  // the image's domain outline (image pixels), not an object
      ++traceNumber;
      Trace trace;
      trace.name = contour.attribute("name").value();
      const std::string traceWhere = where + ", trace " + (trace.name.empty() ? std::string() : "\"" + trace.name + "\" ") +
                                     "(#" + std::to_string(traceNumber) + " in the section)";
      if (trace.name.empty()) return invalid(traceWhere + ": no name");
      trace.closed = parseBool(contour.attribute("closed"), true);
      trace.color = parseColor(contour.attribute("border"));
      if (!trace.closed) {
        section.traces.push_back(std::move(trace));
        continue;
      }
      if (!transform) {
        SCANSURF_ASSIGN_OR_RETURN(ReconstructTransform t,
                                  readTransform(transformNode, where + ", Transform #" + std::to_string(transformNumber)));
        transform = t;
      }
      const pugi::xml_attribute points = contour.attribute("points");
      if (!points) return invalid(traceWhere + ": missing attribute points");
      std::string bad;
      const auto values = parseNumbers(points.value(), bad);
      if (!values) return invalid(traceWhere + ": points hold \"" + bad + "\", not a number");
      if (values->size() % 2 != 0)
        return invalid(traceWhere + ": points hold " + std::to_string(values->size()) + " numbers, not x y pairs");
      trace.points.reserve(values->size() / 2);
      for (std::size_t i = 0; i < values->size(); i += 2) {
        auto p = transform->inverse({(*values)[i], (*values)[i + 1]});
        if (!p) return invalid(traceWhere + ", point " + std::to_string(i / 2 + 1) + ": " + p.error().message);
        // A Transform far off (a translation of 1e20) maps every point of a trace onto one double:
        // the trace would vanish as degenerate and its section with it, so it is refused here.
        if (!(std::abs(p->x) <= kMaxCoordinate && std::abs(p->y) <= kMaxCoordinate))
          return invalid(traceWhere + ", point " + std::to_string(i / 2 + 1) + ": its Transform maps it to (" +
                         formatNumber(p->x) + ", " + formatNumber(p->y) + "), beyond " + formatNumber(kMaxCoordinate) +
                         " units from the origin");
        trace.points.push_back(*p);
      }
      section.traces.push_back(std::move(trace));
    }
  }
  return section;
}

// "name.123" -> true (digits after the series name and a dot).
bool isSectionFileOf(const std::string& filename, const std::string& series) {
  if (filename.size() <= series.size() + 1 || filename.compare(0, series.size(), series) != 0 || filename[series.size()] != '.')
    return false;
  return std::all_of(filename.begin() + static_cast<std::ptrdiff_t>(series.size() + 1), filename.end(),
                     [](unsigned char c) { return std::isdigit(c); });
}

// The series name of a section file name "name.123", or nullopt.
std::optional<std::string> seriesOfSectionFile(const std::string& filename) {
  const auto dot = filename.rfind('.');
  if (dot == std::string::npos || dot == 0) return std::nullopt;
  const std::string name = filename.substr(0, dot);
  return isSectionFileOf(filename, name) ? std::optional<std::string>(name) : std::nullopt;
}

Result<std::vector<fs::path>> sectionFiles(const fs::path& dir, const std::string& series) {
  std::vector<fs::path> files;
  std::error_code ec;
  for (fs::directory_iterator it(dir.empty() ? fs::path(".") : dir, ec), end; !ec && it != end; it.increment(ec))
    if (isSectionFileOf(it->path().filename().string(), series) && it->is_regular_file()) files.push_back(it->path());
  if (ec) return makeError(Errc::Io, dir.string() + ": cannot list the folder: " + ec.message());
  std::sort(files.begin(), files.end());
  return files;
}

// Reconstruct's unit names as ContourSet units.
std::string unitsOf(std::string units) {
  std::string lower = units;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (lower.empty() || lower == "microns" || lower == "micron" || lower == "um" || lower == "micrometers" ||
      lower == "micrometres" || lower == "\xC2\xB5m")
    return "\xC2\xB5m";  // µm
  if (lower == "nanometers" || lower == "nanometres" || lower == "nm") return "nm";
  if (lower == "millimeters" || lower == "millimetres" || lower == "mm") return "mm";
  return units;
}

}  // namespace

Result<ReconstructTransform> ReconstructTransform::fromFile(int dim, const std::vector<double>& xcoef,
                                                            const std::vector<double>& ycoef) {
  if (dim < 0 || dim > 6) return invalid("Transform dim=" + std::to_string(dim) + " (Reconstruct defines 0 to 6)");
  auto at = [](const std::vector<double>& c, std::size_t i) { return i < c.size() ? c[i] : 0.0; };
  for (const auto* c : {&xcoef, &ycoef})
    for (double v : *c)
      if (!std::isfinite(v)) return invalid("Transform coefficient " + formatNumber(v) + " is not finite");
  ReconstructTransform t;
  t.dim = dim;
  switch (dim) {
    case 0: break;
    case 1: t.a[0] = at(xcoef, 0), t.b[0] = at(ycoef, 0); break;
    case 2:  // x' = a0 + a1 x, y' = b0 + b1 y
      t.a = {at(xcoef, 0), at(xcoef, 1), 0, 0, 0, 0};
      t.b = {at(ycoef, 0), 0, at(ycoef, 1), 0, 0, 0};
      break;
    default:  // the first dim terms of the polynomial
      for (std::size_t i = 0; i < 6; ++i) {
        t.a[i] = i < static_cast<std::size_t>(dim) ? at(xcoef, i) : 0.0;
        t.b[i] = i < static_cast<std::size_t>(dim) ? at(ycoef, i) : 0.0;
      }
  }
  return t;
}

Point2 ReconstructTransform::forward(Point2 p) const {
  const double x = p.x, y = p.y;
  return {a[0] + a[1] * x + a[2] * y + a[3] * x * y + a[4] * x * x + a[5] * y * y,
          b[0] + b[1] * x + b[2] * y + b[3] * x * y + b[4] * x * x + b[5] * y * y};
}

Result<Point2> ReconstructTransform::inverse(Point2 q) const {
  // The linear part first: exact for dim 0-3, the starting point for dim 4-6.
  const double det = a[1] * b[2] - a[2] * b[1];
  const double size = (std::abs(a[1]) + std::abs(a[2])) * (std::abs(b[1]) + std::abs(b[2]));
  if (!(std::abs(det) > 1e-12 * size))
    return invalid("the Transform (dim " + std::to_string(dim) + ") is singular: its linear part has determinant " +
                   formatNumber(det));
  const double u = q.x - a[0], v = q.y - b[0];
  double x = (b[2] * u - a[2] * v) / det;
  double y = (a[1] * v - b[1] * u) / det;
  if (a[3] == 0 && a[4] == 0 && a[5] == 0 && b[3] == 0 && b[4] == 0 && b[5] == 0) return Point2{x, y};
  // Newton's method on forward(p) = q (Reconstruct's Nform::XYinverse iterates the same
  // Jacobian from (0, 0); starting from the linear inverse converges to the nearby root).
  const double tolerance = 1e-12 * (1 + std::abs(q.x) + std::abs(q.y));
  for (int iteration = 0; iteration < 100; ++iteration) {
    const Point2 f = forward({x, y});
    const double fx = f.x - q.x, fy = f.y - q.y;
    if (std::abs(fx) + std::abs(fy) <= tolerance) return Point2{x, y};
    const double j11 = a[1] + a[3] * y + 2 * a[4] * x, j12 = a[2] + a[3] * x + 2 * a[5] * y;
    const double j21 = b[1] + b[3] * y + 2 * b[4] * x, j22 = b[2] + b[3] * x + 2 * b[5] * y;
    const double jdet = j11 * j22 - j12 * j21;
    if (!(std::abs(jdet) > 0) || !std::isfinite(jdet)) break;
    x -= (j22 * fx - j12 * fy) / jdet;
    y -= (j11 * fy - j21 * fx) / jdet;
  }
  return invalid("the Transform (dim " + std::to_string(dim) + ") cannot be inverted at (" + formatNumber(q.x) + ", " +
                 formatNumber(q.y) + ")");
}

bool looksLikeReconstructXml(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(4096, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  std::size_t i = head.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
  while (i < head.size() && std::isspace(static_cast<unsigned char>(head[i]))) ++i;
  if (i >= head.size() || head[i] != '<') return false;
  // The first start tag: skip the declaration (<?...?>), comments and DOCTYPE (<!...>).
  for (std::size_t lt = head.find('<', i); lt != std::string::npos && lt + 1 < head.size(); lt = head.find('<', lt + 1)) {
    const char c = head[lt + 1];
    if (c == '?' || c == '!') continue;
    std::size_t end = lt + 1;
    while (end < head.size() && (std::isalnum(static_cast<unsigned char>(head[end])) || head[end] == '_' || head[end] == ':'))
      ++end;
    const std::string name = head.substr(lt + 1, end - lt - 1);
    return name == "Series" || name == "Section";
  }
  return false;
}

namespace {

// Which series the given file opens (a series file, or a section file and the series beside
// it) and, for a section file read alone, its file list.
Result<void> identifySeries(const fs::path& path, const std::string& rootName, ReconstructSeries& out,
                            std::vector<fs::path>& files, std::vector<std::string>& warnings) {
  const std::string given = path.string();
  if (rootName == "Series") {
    out.seriesFile = path;
    out.name = path.stem().string();
    return {};
  }
  if (rootName != "Section")
    return invalid(given + ": XML with root element <" + rootName +
                   ">, not a Reconstruct series (<Series>) or section (<Section>)");
  if (const auto series = seriesOfSectionFile(path.filename().string())) {
    out.name = *series;
    const fs::path ser = path.parent_path() / (*series + ".ser");
    std::error_code ec;
    if (fs::is_regular_file(ser, ec)) out.seriesFile = ser;
  } else {
    out.name = path.stem().string();
    files = {path};  // not named NAME.<number>: this section alone
    warnings.push_back(given + ": a section file not named SERIES.<number>: read alone, without its series");
  }
  if (out.seriesFile.empty())
    warnings.push_back(given + ": no series file " + out.name +
                       ".ser beside it: units microns and zMidSection off "
                       "(Reconstruct's defaults)");
  return {};
}

// The series file's units and zMidSection (the given document when it is the series file).
Result<std::string> readSeriesSettings(const fs::path& path, const pugi::xml_document& doc, ReconstructSeries& out) {
  if (out.seriesFile.empty()) return std::string();
  pugi::xml_document seriesDoc;
  if (out.seriesFile == path) {
    seriesDoc.reset(doc);
  } else {
    SCANSURF_TRY(loadXml(out.seriesFile, seriesDoc));
  }
  const pugi::xml_node series = seriesDoc.document_element();
  if (std::string_view(series.name()) != "Series")
    return invalid(out.seriesFile.string() + ": not a Reconstruct series file (root element <" + series.name() + ">)");
  out.zMidSection = parseBool(series.attribute("zMidSection"), false);
  return std::string(series.attribute("units").value());
}

// Every section, sorted by index (no index twice), each at Reconstruct's section depth
// (SectionsInfo::ZDistance: section 0 stays out of the sum).
Result<std::vector<Section>> readSections(const std::vector<fs::path>& files, ReconstructSeries& out) {
  std::vector<Section> sections;
  for (const fs::path& f : files) {
    SCANSURF_ASSIGN_OR_RETURN(Section s, readSection(f));
    sections.push_back(std::move(s));
  }
  std::stable_sort(sections.begin(), sections.end(), [](const Section& l, const Section& r) { return l.index < r.index; });
  for (std::size_t i = 1; i < sections.size(); ++i)
    if (sections[i].index == sections[i - 1].index)
      return invalid(sections[i].path.string() + ": section index " + std::to_string(sections[i].index) + " is also " +
                     sections[i - 1].path.string() + "'s");
  double below = 0;
  for (Section& s : sections) {
    if (s.index == 0) continue;
    s.z = below + (out.zMidSection ? s.thickness / 2 : s.thickness);
    below += s.thickness;
  }
  out.sections = static_cast<int>(sections.size());
  out.firstIndex = sections.front().index;
  out.lastIndex = sections.back().index;
  return sections;
}

// Objects by name (sorted, as Reconstruct's object list), their closed traces gathered over
// the sections; open traces counted and said.
std::vector<RawObject> collectObjects(std::vector<Section>& sections, const std::string& seriesLabel,
                                      std::vector<std::string>& warnings) {
  struct Collected {
    RawObject object;
    std::optional<Rgb> openColor;
    int open = 0;
  };
  std::map<std::string, Collected> byName;
  for (Section& s : sections)
    for (Trace& t : s.traces) {
      Collected& c = byName[t.name];
      if (!t.closed) {
        ++c.open;
        if (!c.openColor) c.openColor = t.color;
        continue;
      }
      if (!c.object.info.color) c.object.info.color = t.color;
      c.object.closed.push_back(ObjectContour{s.z, std::move(t.points)});
    }
  std::vector<RawObject> objects;
  for (auto& [name, c] : byName) {
    c.object.info.name = name;
    c.object.info.number = static_cast<int>(objects.size()) + 1;
    if (!c.object.info.color) c.object.info.color = c.openColor;
    c.object.info.skipped = c.open;
    if (c.open > 0)
      warnings.push_back(seriesLabel + ": object \"" + name + "\": skipped " + std::to_string(c.open) + " open trace(s)" +
                         (c.object.closed.empty() ? " (it has no closed trace)" : "") + "; only closed traces are surfaced");
    objects.push_back(std::move(c.object));
  }
  return objects;
}

std::string seriesNote(const ReconstructSeries& out) {
  int surfaced = 0;
  for (const ObjectInfo& o : out.objects) surfaced += o.feature >= 0;
  return "Reconstruct series \"" + out.name + "\": " + std::to_string(out.sections) + " sections (index " +
         std::to_string(out.firstIndex) + ".." + std::to_string(out.lastIndex) + "), " + std::to_string(out.objects.size()) +
         " objects, " + std::to_string(surfaced) + " surfaced; units " + out.contours.units +
         "; z = depth through the section thicknesses (" + (out.zMidSection ? "section middles" : "section tops") + ")";
}

}  // namespace

Result<ReconstructSeries> readReconstructSeries(const fs::path& path, const ReconstructOptions& options) {
  const std::string given = path.string();
  pugi::xml_document doc;
  SCANSURF_TRY(loadXml(path, doc));
  ReconstructSeries out;
  out.contours.source = given;
  std::vector<std::string> warnings;
  std::vector<fs::path> files;
  SCANSURF_TRY(identifySeries(path, doc.document_element().name(), out, files, warnings));
  SCANSURF_ASSIGN_OR_RETURN(const std::string units, readSeriesSettings(path, doc, out));
  const fs::path dir = path.parent_path();
  if (files.empty()) {
    SCANSURF_ASSIGN_OR_RETURN(files, sectionFiles(dir, out.name));
    if (files.empty())
      return invalid(given + ": no section files " + out.name + ".<number> beside it in " +
                     (dir.empty() ? std::string(".") : dir.string()));
  }
  SCANSURF_ASSIGN_OR_RETURN(std::vector<Section> sections, readSections(files, out));
  std::vector<RawObject> objects = collectObjects(sections, out.seriesFile.empty() ? given : out.seriesFile.string(), warnings);
  out.contours.units = unitsOf(units);
  out.contours.warnings = warnings;
  SCANSURF_ASSIGN_OR_RETURN(out.objects,
                            buildObjectFeatures(objects, {options.objectPatterns, options.requireFeatures}, out.contours));
  out.contours.notes.push_back(seriesNote(out));
  if (!out.seriesFile.empty()) out.contours.files.push_back(out.seriesFile.string());
  for (const fs::path& f : files) out.contours.files.push_back(f.string());
  return out;
}

}  // namespace scansurf
