// scansurf: writes an electron-microscopy example of each tracing format with the test
// writers (support/em_writers): a Reconstruct series and an IMOD model of a piece of neuropil.
// Usage: scansurf_make_em_examples OUTDIR   (writes OUTDIR/neuropil/neuropil.ser + sections
// and OUTDIR/neuropil.mod)
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>

#include "support/em_writers.h"

namespace {

using scansurf::Point2;
using namespace scansurf::test;

std::vector<Point2> ellipse(double cx, double cy, double rx, double ry, int n, double turn = 0) {
  std::vector<Point2> pts;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * i / n + turn;
    pts.push_back({cx + rx * std::cos(a), cy + ry * std::sin(a)});
  }
  return pts;
}

// Reconstruct, in µm: 60 sections of 45-55 nm, the trace Transform of section k of dim k % 7
// (a slightly different alignment each). A dendrite shaft drifting across the sections
// ("d01") holding a mitochondrion ("m01", nested), four spines beside it ("d01s1".."d01s4"),
// a myelinated axon ("a01", an annulus: a tube), an axon that branches ("a02"), open
// vesicle-cluster marks ("vc", skipped), hidden traces on every fifth section.
TestSeries neuropilSeries() {
  TestSeries series;
  series.name = "neuropil";
  for (int k = 1; k <= 60; ++k) {
    TestSection section;
    section.index = k;
    section.thickness = 0.045 + 0.01 * ((k * 7) % 11) / 10.0;
    TestTransform image;
    image.image = true;
    section.transforms.push_back(image);
    TestTransform t;
    t.dim = k % 7;
    const double c = std::cos(0.01 * k), s = std::sin(0.01 * k);
    switch (t.dim) {
      case 1: t.xcoef = {0.02 * k, 1, 0, 0, 0, 0}, t.ycoef = {-0.01 * k, 0, 1, 0, 0, 0}; break;
      case 2: t.xcoef = {0.1, 1.01, 0, 0, 0, 0}, t.ycoef = {0.05, 0.99, 0, 0, 0, 0}; break;
      case 3: t.xcoef = {0.1, c, -s, 0, 0, 0}, t.ycoef = {-0.1, s, c, 0, 0, 0}; break;
      case 4: t.xcoef = {0.05, c, -s, 0.002, 0, 0}, t.ycoef = {0.02, s, c, -0.001, 0, 0}; break;
      case 5: t.xcoef = {0, 1, 0.01, 0.001, 0.0005, 0}, t.ycoef = {0, -0.01, 1, 0.0005, -0.0004, 0}; break;
      case 6: t.xcoef = {0.03, 0.99, 0.02, 0.001, 0.0003, -0.0004}, t.ycoef = {-0.02, 0.01, 1.01, -0.0008, 0.0002, 0.0005}; break;
      default: break;
    }
    const bool hidden = k % 5 == 0;
    const double drift = 0.01 * k;
    TestTrace shaft{"d01", ellipse(3 + drift, 3, 0.6, 0.5, 48), true, hidden, {0.5, 0.5, 1}};
    t.traces.push_back(shaft);
    if (k >= 18 && k <= 40)
      t.traces.push_back(TestTrace{"m01", ellipse(3 + drift, 3, 0.3, 0.15, 32, 0.02 * k), true, hidden, {1, 0.3, 0.3}});
    for (int spine = 1; spine <= 4; ++spine) {
      const int first = 6 + 12 * (spine - 1);
      if (k < first || k > first + 8) continue;
      const double angle = spine * 1.4;
      const double r = 0.6 + 0.12 + 0.02 * (k - first);
      t.traces.push_back(TestTrace{"d01s" + std::to_string(spine),
                                   ellipse(3 + drift + r * std::cos(angle), 3 + r * std::sin(angle), 0.11, 0.11, 20),
                                   true,
                                   false,
                                   {1, 0.8, 0.2}});
    }
    t.traces.push_back(TestTrace{"a01", ellipse(6, 1.5, 0.45, 0.45, 40), true, hidden, {0.2, 0.9, 0.2}});
    t.traces.push_back(TestTrace{"a01", ellipse(6, 1.5, 0.3, 0.3, 40), true, hidden, {0.2, 0.9, 0.2}});
    if (k <= 30) {
      t.traces.push_back(TestTrace{"a02", ellipse(1, 5.5, 0.35, 0.25, 32), true, false, {0.9, 0.2, 0.9}});
    } else {
      const double split = 0.012 * (k - 30);  // the branches apart from the first section on
      t.traces.push_back(TestTrace{"a02", ellipse(1 - 0.2 - split, 5.5, 0.16, 0.2, 24), true, false, {0.9, 0.2, 0.9}});
      t.traces.push_back(TestTrace{"a02", ellipse(1 + 0.2 + split, 5.5, 0.16, 0.2, 24), true, false, {0.9, 0.2, 0.9}});
    }
    if (k % 10 == 3) t.traces.push_back(TestTrace{"vc", {{4.5, 4.5}, {4.7, 4.6}, {4.9, 4.5}}, false, false, {1, 1, 0}});
    section.transforms.push_back(t);
    series.sections.push_back(section);
  }
  return series;
}

TestImodContour planar(const std::vector<Point2>& pts, float z, std::uint32_t flags = 0) {
  TestImodContour c;
  c.flags = flags;
  for (const Point2& p : pts) c.points.push_back({static_cast<float>(p.x), static_cast<float>(p.y), z});
  return c;
}

// IMOD, 5 nm pixels, 50 nm sections (zscale 10), µm: a cell outline on 50 sections, a nucleus
// inside it, two mitochondria inside it too (one branching), an open ER object and scattered vesicles
// (both skipped), a mesh chunk and a material chunk as 3dmod writes them.
TestImodModel neuropilModel() {
  TestImodModel m;
  m.name = "neuropil.mod";
  m.pixelSize = 0.005f;
  m.units = -6;
  m.scale = {1, 1, 10};
  TestImodObject cell{"cell", 0, {0.6f, 0.6f, 0.6f}, {}, true, true};
  TestImodObject nucleus{"nucleus", 0, {0.2f, 0.2f, 1}, {}};
  TestImodObject mito1{"mitochondrion", 0, {1, 0.2f, 0.2f}, {}};
  TestImodObject mito2{"mitochondrion", 0, {1, 0.5f, 0.2f}, {}};
  TestImodObject er{"ER", 1u << 3, {0.2f, 1, 0.2f}, {}};
  TestImodObject vesicles{"vesicles", 1u << 9, {1, 1, 0}, {}};
  for (int z = 0; z < 50; ++z) {
    const float fz = static_cast<float>(z);
    const double swell = 1 + 0.1 * std::sin(z * 0.12);
    cell.contours.push_back(planar(ellipse(600, 600, 450 * swell, 380 * swell, 96), fz));
    if (z >= 8 && z <= 40) nucleus.contours.push_back(planar(ellipse(560, 620, 180, 150, 64, 0.01 * z), fz));
    if (z >= 5 && z <= 25) mito1.contours.push_back(planar(ellipse(850, 450, 60, 25, 32, 0.05 * z), fz));
    if (z >= 20 && z <= 45) {
      if (z < 33) {
        mito2.contours.push_back(planar(ellipse(600, 330, 70, 30, 32), fz));
      } else {
        mito2.contours.push_back(planar(ellipse(560 - 3 * (z - 33), 330, 30, 28, 24), fz));
        mito2.contours.push_back(planar(ellipse(640 + 3 * (z - 33), 330, 30, 28, 24), fz));
      }
    }
    if (z % 4 == 0) er.contours.push_back(planar(ellipse(700, 750, 80, 20, 16), fz));
    if (z % 7 == 0) vesicles.contours.push_back(planar({{500, 300}, {520, 310}, {540, 300}}, fz));
  }
  m.objects = {cell, nucleus, mito1, mito2, er, vesicles};
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUTDIR\n", argv[0]);
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  writeReconstructSeries(neuropilSeries(), dir / "neuropil");
  writeImodModel(neuropilModel(), dir / "neuropil.mod");
  std::printf("wrote %s and %s\n", (dir / "neuropil" / "neuropil.ser").string().c_str(), (dir / "neuropil.mod").string().c_str());
  return 0;
}
