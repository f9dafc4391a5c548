#include "support/em_writers.h"

#include <bit>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace scansurf::test {

namespace fs = std::filesystem;

namespace {

std::string number(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

std::string coefficients(const std::array<double, 6>& c) {
  std::string s;
  for (double v : c) {
    s += ' ';
    s += number(v);
  }
  return s;
}

std::string color(const std::array<double, 3>& c) { return number(c[0]) + " " + number(c[1]) + " " + number(c[2]); }

// Points as Reconstruct writes them: "x y," per line.
std::string points(const std::vector<Point2>& pts) {
  std::string s;
  for (const Point2& p : pts) s += number(p.x) + " " + number(p.y) + ",\n\t";
  return s;
}

void writeText(const std::string& text, const fs::path& path) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

}  // namespace

Point2 reconstructForward(int dim, const std::array<double, 6>& a, const std::array<double, 6>& b, Point2 p) {
  const double x = p.x, y = p.y;
  switch (dim) {
    case 0: return p;
    case 1: return {a[0] + x, b[0] + y};
    case 2: return {a[0] + a[1] * x, b[0] + b[1] * y};
    case 3: return {a[0] + a[1] * x + a[2] * y, b[0] + b[1] * x + b[2] * y};
    case 4: return {a[0] + (a[1] + a[3] * y) * x + a[2] * y, b[0] + (b[1] + b[3] * y) * x + b[2] * y};
    case 5: return {a[0] + (a[1] + a[3] * y + a[4] * x) * x + a[2] * y, b[0] + (b[1] + b[3] * y + b[4] * x) * x + b[2] * y};
    default:
      return {a[0] + (a[1] + a[3] * y + a[4] * x) * x + (a[2] + a[5] * y) * y,
              b[0] + (b[1] + b[3] * y + b[4] * x) * x + (b[2] + b[5] * y) * y};
  }
}

void writeReconstructSeries(const TestSeries& series, const fs::path& dir) {
  fs::create_directories(dir);
  if (series.writeSeriesFile) {
    std::string s = "<?xml version=\"1.0\"?>\n<!DOCTYPE Series SYSTEM \"series.dtd\">\n\n";
    s += "<Series index=\"" + std::to_string(series.sections.empty() ? 1 : series.sections.front().index) +
         "\" viewport=\"0 0 0.00254\"\n\tunits=\"" + series.units +
         "\"\n\tautoSaveSeries=\"true\"\n\tdefaultThickness=\"0.05\"\n\tzMidSection=\"" +
         (series.zMidSection ? "true" : "false") + "\"\n\tthumbWidth=\"128\">\n";
    // The trace palette: not objects.
    s += "<Contour name=\"palette\" closed=\"true\" border=\"1 0 0\" fill=\"1 0 0\" mode=\"9\"\n points=\"-3 1,\n\t-3 -1,\n\t3 "
         "-1,\n\t3 1,\n\t\"/>\n";
    s += "</Series>\n\n";
    writeText(s, dir / (series.name + ".ser"));
  }
  for (const TestSection& section : series.sections) {
    std::string s = "<?xml version=\"1.0\"?>\n<!DOCTYPE Section SYSTEM \"section.dtd\">\n\n";
    s += "<Section index=\"" + std::to_string(section.index) + "\" thickness=\"" + number(section.thickness) +
         "\" alignLocked=\"true\">\n";
    for (const TestTransform& t : section.transforms) {
      s += "<Transform dim=\"" + std::to_string(t.dim) + "\"\n xcoef=\"" + coefficients(t.xcoef) + "\"\n ycoef=\"" +
           coefficients(t.ycoef) + "\">\n";
      if (t.image) {
        s += "<Image mag=\"0.002\" contrast=\"1\" brightness=\"0\" red=\"true\" green=\"true\" blue=\"true\"\n"
             " src=\"section" +
             std::to_string(section.index) + ".tif\" />\n";
        s += "<Contour name=\"domain1\" hidden=\"false\" closed=\"true\" simplified=\"false\" border=\"1 0 1\" "
             "fill=\"1 0 1\" mode=\"11\"\n points=\"0 0,\n\t4096 0,\n\t4096 4096,\n\t0 4096,\n\t\"/>\n";
      } else {
        for (const TestTrace& trace : t.traces) {
          std::vector<Point2> stored;
          for (const Point2& p : trace.points) stored.push_back(reconstructForward(t.dim, t.xcoef, t.ycoef, p));
          s += "<Contour name=\"" + trace.name + "\" hidden=\"" + (trace.hidden ? "true" : "false") + "\" closed=\"" +
               (trace.closed ? "true" : "false") + "\" simplified=\"true\" border=\"" + color(trace.border) + "\" fill=\"" +
               color(trace.border) + "\" mode=\"13\"\n points=\"" + points(stored) + "\"/>\n";
        }
      }
      s += "</Transform>\n\n";
    }
    s += "</Section>\n\n";
    writeText(s, dir / (series.name + "." + std::to_string(section.index)));
  }
}

// ------------------------------------------------------------------------------------ IMOD

namespace {

class BigEndian {
 public:
  void id(const char* four) { bytes.append(four, 4); }
  void i32(std::int32_t v) { u32(static_cast<std::uint32_t>(v)); }
  void u32(std::uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8) bytes.push_back(static_cast<char>((v >> shift) & 0xff));
  }
  void i16(std::int16_t v) {
    bytes.push_back(static_cast<char>((static_cast<std::uint16_t>(v) >> 8) & 0xff));
    bytes.push_back(static_cast<char>(static_cast<std::uint16_t>(v) & 0xff));
  }
  void f32(float v) { u32(std::bit_cast<std::uint32_t>(v)); }
  void u8(unsigned v) { bytes.push_back(static_cast<char>(v & 0xff)); }
  void text(const std::string& s, std::size_t field) {
    std::string t = s.substr(0, field - 1);
    t.resize(field, '\0');
    bytes += t;
  }
  std::string bytes;
};

}  // namespace

std::string imodModelBytes(const TestImodModel& model) {
  BigEndian out;
  out.id("IMOD");
  out.id("V1.2");
  // The 232-byte model header.
  out.text(model.name, 128);
  out.i32(512), out.i32(512), out.i32(100);  // xmax, ymax, zmax
  out.i32(static_cast<std::int32_t>(model.objects.size()));
  out.u32(0xF000);                         // flags
  out.i32(1), out.i32(1);                  // drawmode, mousemode
  out.i32(0), out.i32(255);                // blacklevel, whitelevel
  out.f32(0), out.f32(0), out.f32(0);      // offsets
  for (float s : model.scale) out.f32(s);  // xscale, yscale, zscale
  out.i32(0), out.i32(0), out.i32(0);      // object, contour, point
  out.i32(3), out.i32(128);                // res, thresh
  out.f32(model.pixelSize);
  out.i32(model.units);
  out.i32(0);                          // csum
  out.f32(0), out.f32(0), out.f32(0);  // alpha, beta, gamma
  if (out.bytes.size() != 8 + 232) throw std::logic_error("IMOD model header size");
  bool first = true;
  for (const TestImodObject& o : model.objects) {
    const std::size_t start = out.bytes.size();
    out.id("OBJT");
    out.text(o.name, 64);
    for (int i = 0; i < 16; ++i) out.u32(0);  // extra
    out.i32(static_cast<std::int32_t>(o.contours.size()));
    out.u32(o.flags);
    out.i32(0), out.i32(1);  // axis, drawmode
    out.f32(o.color[0]), out.f32(o.color[1]), out.f32(o.color[2]);
    out.i32(1);  // pdrawsize
    out.u8(1), out.u8(3), out.u8(1), out.u8(1), out.u8(0), out.u8(0), out.u8(0), out.u8(0);
    out.i32(o.mesh ? 1 : 0), out.i32(0);  // meshsize, surfsize
    if (out.bytes.size() - start != 4 + 176) throw std::logic_error("IMOD object size");
    for (const TestImodContour& c : o.contours) {
      out.id("CONT");
      out.i32(static_cast<std::int32_t>(c.points.size()));
      out.u32(c.flags);
      out.i32(0), out.i32(0);  // time, surf
      for (const auto& p : c.points) out.f32(p[0]), out.f32(p[1]), out.f32(p[2]);
    }
    if (o.mesh) {
      out.id("MESH");
      out.i32(3), out.i32(5);  // vertices, indices
      out.u32(0), out.i16(0), out.i16(0);
      for (int v = 0; v < 9; ++v) out.f32(static_cast<float>(v));
      for (std::int32_t index : {-25, 0, 1, 2, -22}) out.i32(index);  // polygon start, triangle, end
    }
    if (o.material) {
      out.id("IMAT");
      out.i32(16);
      for (int i = 0; i < 16; ++i) out.u8(static_cast<unsigned>(i * 7));
    }
    if (model.unknownChunks && first) {
      out.id("ZZZZ");
      out.i32(10);
      for (int i = 0; i < 10; ++i) out.u8(0x49);  // 'I': must not be read as a chunk id
    }
    first = false;
  }
  if (model.unknownChunks) {
    out.id("MINX");
    out.i32(72);
    for (int i = 0; i < 18; ++i) out.f32(1);
  }
  out.id("IEOF");
  return out.bytes;
}

void writeBytes(const std::string& bytes, const fs::path& path) { writeText(bytes, path); }

void writeImodModel(const TestImodModel& model, const fs::path& path) { writeBytes(imodModelBytes(model), path); }

}  // namespace scansurf::test
