// Separating-surface assembly (Nielson & Franke, "Computing the separating surface for
// segmented data", IEEE Visualization 1997; as used by the scanline surfacing paper, §3.5).
// Each tetrahedron is cut into the regions nearest its corners: with two labels, the flat
// polygon through the midpoints of the edges joining them; with three or more, the boundary
// curves on its faces coned to its centroid. Vertices live on an integer lattice of 1/12 cell,
// so identity and orientation are exact.
#include "geometry/extraction/assembly.h"

#include <algorithm>
#include <array>
#include <bit>
#include <iterator>
#include <span>
#include <utility>
#include <vector>

#include "core/parallel.h"

namespace scansurf {
namespace {

using Vec3i = std::array<int, 3>;

// One triangle of the case table, in cell-local twelfths (0..12 per axis).
struct LocalTriangle {
  std::array<Vec3i, 3> v;
  // Cell corners whose labels the triangle separates; wound so its normal points from
  // `from`'s region into `to`'s.
  std::uint8_t from = 0;
  std::uint8_t to = 0;
};

constexpr int kCodes = 1 << SCANSURF_TET_CODE_BITS;

struct CaseTable {
  std::vector<LocalTriangle> triangles;
  // [tet * kCodes + code] -> {first, count} into triangles; invalid codes are empty.
  std::array<std::array<std::uint32_t, 2>, SCANSURF_TETS_PER_CELL * kCodes> range{};
};

Vec3i cornerPosition(int corner) {
  return {12 * kCellCorners[corner][0], 12 * kCellCorners[corner][1], 12 * kCellCorners[corner][2]};
}

Vec3i average(std::initializer_list<int> corners) {
  Vec3i sum{0, 0, 0};
  for (int c : corners) {
    const Vec3i p = cornerPosition(c);
    for (int a = 0; a < 3; ++a) sum[a] += p[a];
  }
  const int n = static_cast<int>(corners.size());
  return {sum[0] / n, sum[1] / n, sum[2] / n};  // exact: 12 is divisible by 2, 3 and 4
}

// Groups of the four tet-local corners encoded by a partition code; false if the code is not
// a valid restricted-growth code (see shaders/shared/cell_case.h).
bool decodePartition(std::uint32_t code, std::array<int, 4>& group, int& groups) {
  const std::array<std::uint32_t, 4> r = {0u, code & 1u, (code >> 1) & 3u, (code >> 3) & 3u};
  group = {0, 0, 0, 0};
  groups = 1;
  for (std::uint32_t i = 1; i < 4; ++i) {
    if (r[i] > i) return false;
    if (r[i] == i) {
      group[i] = groups++;
    } else {
      if (r[r[i]] != r[i]) return false;  // must point at the first corner of its label
      group[i] = group[r[i]];
    }
  }
  return true;
}

void addOriented(std::vector<LocalTriangle>& out, Vec3i a, Vec3i b, Vec3i c, int from, int to) {
  const Vec3i u = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const Vec3i v = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const Vec3i n = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  const Vec3i pf = cornerPosition(from);
  const Vec3i pt = cornerPosition(to);
  const long long side = static_cast<long long>(n[0]) * (pt[0] - pf[0]) + static_cast<long long>(n[1]) * (pt[1] - pf[1]) +
                         static_cast<long long>(n[2]) * (pt[2] - pf[2]);
  // The triangle's plane strictly separates the two corners, so side is never 0.
  LocalTriangle t;
  t.v = side > 0 ? std::array<Vec3i, 3>{a, b, c} : std::array<Vec3i, 3>{a, c, b};
  t.from = static_cast<std::uint8_t>(from);
  t.to = static_cast<std::uint8_t>(to);
  out.push_back(t);
}

void addTetCase(std::vector<LocalTriangle>& out, const std::array<int, 4>& tet, const std::array<int, 4>& group, int groups) {
  if (groups == 2) {
    std::array<int, 4> in{}, rest{};
    int nIn = 0, nRest = 0;
    for (int i = 0; i < 4; ++i) (group[i] == 0 ? in[nIn++] : rest[nRest++]) = tet[i];
    if (nIn == 2) {
      // 2+2: the planar quad of the four cross-edge midpoints, split along m(u0,v0)-m(u1,v1).
      const Vec3i m00 = average({in[0], rest[0]}), m01 = average({in[0], rest[1]});
      const Vec3i m11 = average({in[1], rest[1]}), m10 = average({in[1], rest[0]});
      addOriented(out, m00, m01, m11, in[0], rest[0]);
      addOriented(out, m00, m11, m10, in[0], rest[0]);
      return;
    }
    // 3+1: one triangle cutting off the lone corner.
    const bool loneIn = nIn == 1;
    const int lone = loneIn ? in[0] : rest[0];
    const std::array<int, 4>& others = loneIn ? rest : in;
    addOriented(out, average({lone, others[0]}), average({lone, others[1]}), average({lone, others[2]}), lone, others[0]);
    return;
  }
  // Three or more labels: each face's boundary curve coned to the tet centroid.
  const Vec3i centroid = average({tet[0], tet[1], tet[2], tet[3]});
  for (int omit = 0; omit < 4; ++omit) {
    std::array<int, 3> f{};  // tet-local corners of the face
    int n = 0;
    for (int i = 0; i < 4; ++i)
      if (i != omit) f[n++] = i;
    const int g0 = group[f[0]], g1 = group[f[1]], g2 = group[f[2]];
    if (g0 == g1 && g1 == g2) continue;
    if (g0 != g1 && g1 != g2 && g0 != g2) {
      const Vec3i faceCentroid = average({tet[f[0]], tet[f[1]], tet[f[2]]});
      for (int e = 0; e < 3; ++e) {
        const int p = tet[f[e]], q = tet[f[(e + 1) % 3]];
        addOriented(out, average({p, q}), faceCentroid, centroid, p, q);
      }
      continue;
    }
    // Two labels on the face: the lone corner's segment.
    const int lone = g1 == g2 ? 0 : (g0 == g2 ? 1 : 2);
    const int a = tet[f[lone]], b = tet[f[(lone + 1) % 3]], c = tet[f[(lone + 2) % 3]];
    addOriented(out, average({a, b}), average({a, c}), centroid, a, b);
  }
}

CaseTable buildCaseTable() {
  CaseTable table;
  for (int t = 0; t < SCANSURF_TETS_PER_CELL; ++t) {
    for (int code = 0; code < kCodes; ++code) {
      std::array<int, 4> group{};
      int groups = 0;
      const auto first = static_cast<std::uint32_t>(table.triangles.size());
      if (decodePartition(static_cast<std::uint32_t>(code), group, groups) && groups > 1)
        addTetCase(table.triangles, kCellTets[t], group, groups);
      table.range[t * kCodes + code] = {first, static_cast<std::uint32_t>(table.triangles.size()) - first};
    }
  }
  return table;
}

const CaseTable& caseTable() {
  static const CaseTable table = buildCaseTable();
  return table;
}

std::uint32_t triangleCountOf(const CaseTable& table, const CellCase& c) {
  std::uint32_t n = 0;
  for (int t = 0; t < SCANSURF_TETS_PER_CELL; ++t) n += table.range[t * kCodes + tetCode(c, t)][1];
  return n;
}

// Assembly works in blocks of consecutive surface cells (a few cell layers on a clinical set): each block's
// vertex keys are sorted and made unique in a scratch array of a few MiB that stays in cache
// and is reused, instead of one array of every triangle's keys (24 bytes per triangle, 150 MiB
// on a clinical set) and a sorted copy of it. Blocks depend on the records only, so the mesh
// is the same for any thread count.
constexpr std::size_t kBlockCells = std::size_t{1} << 16;

struct Blocks {
  std::size_t count = 0;
  std::vector<std::size_t> firstTriangle;  // count + 1 entries
  std::span<const CellCase> cases(std::span<const CellCase> all, std::size_t b) const {
    const std::size_t begin = b * kBlockCells;
    return all.subspan(begin, std::min(kBlockCells, all.size() - begin));
  }
};

Blocks planBlocks(const CaseTable& table, std::span<const CellCase> cases, int threads) {
  Blocks blocks;
  blocks.count = (cases.size() + kBlockCells - 1) / kBlockCells;
  blocks.firstTriangle.assign(blocks.count + 1, 0);
  parallelChunks(blocks.count, threads, [&](int, std::size_t b0, std::size_t b1) {
    for (std::size_t b = b0; b < b1; ++b) {
      std::size_t n = 0;
      for (const CellCase& c : blocks.cases(cases, b)) n += triangleCountOf(table, c);
      blocks.firstTriangle[b + 1] = n;
    }
  });
  for (std::size_t b = 0; b < blocks.count; ++b) blocks.firstTriangle[b + 1] += blocks.firstTriangle[b];
  return blocks;
}

// The vertex keys of the block's triangles (3 per triangle) into `keys`, their label pairs into
// `labels` (2 per triangle), each wound from the smaller label to the larger.
void emitTriangles(const CaseTable& table, const Grid& grid, std::span<const CellCase> cases, std::size_t triangles,
                   std::vector<std::uint64_t>& keys, Label* labels) {
  const auto cellsX = static_cast<std::uint64_t>(grid.nx - 1);
  const auto cellsY = static_cast<std::uint64_t>(grid.ny - 1);
  keys.resize(3 * triangles);
  std::uint64_t* out = keys.data();
  for (const CellCase& c : cases) {
    const std::uint64_t ci = c.cell % cellsX;
    const std::uint64_t cj = (c.cell / cellsX) % cellsY;
    const std::uint64_t ck = c.cell / cellsX / cellsY;
    for (int t = 0; t < SCANSURF_TETS_PER_CELL; ++t) {
      const auto& r = table.range[t * kCodes + tetCode(c, t)];
      for (std::uint32_t n = 0; n < r[1]; ++n) {
        const LocalTriangle& lt = table.triangles[r[0] + n];
        std::array<std::uint64_t, 3> k{};
        for (int v = 0; v < 3; ++v)
          k[v] = packVertexKey(12 * ci + static_cast<std::uint64_t>(lt.v[v][0]), 12 * cj + static_cast<std::uint64_t>(lt.v[v][1]),
                               12 * ck + static_cast<std::uint64_t>(lt.v[v][2]));
        const Label la = cellCornerLabel(c, lt.from);
        const Label lb = cellCornerLabel(c, lt.to);
        const bool keep = la < lb;  // else reverse the winding so it points from min to max
        *out++ = k[0];
        *out++ = keep ? k[1] : k[2];
        *out++ = keep ? k[2] : k[1];
        *labels++ = keep ? la : lb;
        *labels++ = keep ? lb : la;
      }
    }
  }
}

// One thread's working memory for indexBlock, reused by its blocks.
struct IndexScratch {
  std::vector<std::uint64_t> pairs, sorted;
  std::vector<std::uint32_t> count;
};

// The block's keys less their least x, y and z, packed (z, y, x) into one number that orders as
// the keys do, above `indexBits` bits that hold the key's index; false if they do not fit 64.
bool packRelative(const std::vector<std::uint64_t>& keys, int indexBits, std::vector<std::uint64_t>& pairs,
                  std::uint64_t& range) {
  std::uint64_t low[3] = {kKeyMask, kKeyMask, kKeyMask}, high[3] = {0, 0, 0};
  for (const std::uint64_t key : keys)
    for (int a = 0; a < 3; ++a) {
      const std::uint64_t c = (key >> (a * kKeyBits)) & kKeyMask;
      low[a] = std::min(low[a], c), high[a] = std::max(high[a], c);
    }
  const std::uint64_t rx = high[0] - low[0] + 1, ry = high[1] - low[1] + 1, rz = high[2] - low[2] + 1;
  range = rx * ry * rz;  // each at most 2^21: no overflow
  if (indexBits >= 64 || (range - 1) >> (64 - indexBits) != 0) return false;
  pairs.resize(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const std::uint64_t key = keys[i];
    const std::uint64_t x = (key & kKeyMask) - low[0], y = ((key >> kKeyBits) & kKeyMask) - low[1],
                        z = ((key >> (2 * kKeyBits)) & kKeyMask) - low[2];
    pairs[i] = ((z * ry + y) * rx + x) << indexBits | i;
  }
  return true;
}

// One stable counting-sort pass over kDigitBits of the pairs from bit `shift`: few enough
// buckets that the scattered writes stay in cache.
constexpr int kDigitBits = 11;
constexpr std::uint64_t kDigitMask = (std::uint64_t{1} << kDigitBits) - 1;
void radixPass(const std::vector<std::uint64_t>& from, std::vector<std::uint64_t>& to, int shift,
               std::vector<std::uint32_t>& count) {
  count.assign(kDigitMask + 1, 0);
  for (const std::uint64_t p : from) ++count[(p >> shift) & kDigitMask];
  std::uint32_t sum = 0;
  for (std::uint32_t& c : count) sum += std::exchange(c, sum);
  to.resize(from.size());
  for (const std::uint64_t p : from) to[count[(p >> shift) & kDigitMask]++] = p;
}

// Pass 1 of a block: its sorted unique keys, and its triangles' corners as indices into them.
// A block spans a few layers of cells, so its keys relative to their least corner and each
// key's index fit one 64-bit word: the words sort in a few radix passes over the key's bits and
// the ranks fall out of one walk, where sorting the keys and searching each corner's took 90 %
// of assembly. Otherwise that way.
std::vector<std::uint64_t> indexBlock(const std::vector<std::uint64_t>& keys, IndexScratch& s, std::uint32_t* corners) {
  std::vector<std::uint64_t> unique;
  const int indexBits = std::max(1, static_cast<int>(std::bit_width(keys.size())));
  std::uint64_t range = 0;
  if (packRelative(keys, indexBits, s.pairs, range)) {
    const int digits = std::max(1, (static_cast<int>(std::bit_width(range - 1)) + kDigitBits - 1) / kDigitBits);
    for (int digit = 0; digit < digits; ++digit) {
      radixPass(s.pairs, s.sorted, indexBits + digit * kDigitBits, s.count);
      s.sorted.swap(s.pairs);
    }
    const std::uint64_t indexMask = (std::uint64_t{1} << indexBits) - 1;
    std::uint64_t previous = UINT64_MAX;
    for (const std::uint64_t p : s.pairs) {
      const std::uint64_t i = p & indexMask;
      if (p >> indexBits != previous) unique.push_back(keys[i]), previous = p >> indexBits;
      corners[i] = static_cast<std::uint32_t>(unique.size() - 1);
    }
    return unique;
  }
  s.sorted.assign(keys.begin(), keys.end());
  std::sort(s.sorted.begin(), s.sorted.end());
  unique.assign(s.sorted.begin(), std::unique(s.sorted.begin(), s.sorted.end()));
  for (std::size_t i = 0; i < keys.size(); ++i)
    corners[i] = static_cast<std::uint32_t>(std::lower_bound(unique.begin(), unique.end(), keys[i]) - unique.begin());
  return unique;
}

// Every block's keys in one sorted unique list. Blocks follow the cells, so the list is nearly
// sorted already; only keys on the faces between blocks repeat.
std::vector<std::uint64_t> mergeKeys(const std::vector<std::vector<std::uint64_t>>& blockKeys) {
  std::size_t total = 0;
  for (const auto& k : blockKeys) total += k.size();
  std::vector<std::uint64_t> all;
  all.reserve(total);
  for (const auto& k : blockKeys) {
    if (k.empty()) continue;
    const auto middle = static_cast<std::ptrdiff_t>(all.size());
    const auto from = std::upper_bound(all.begin(), all.end(), k.front()) - all.begin();  // the keys that interleave
    all.insert(all.end(), k.begin(), k.end());
    std::inplace_merge(all.begin() + from, all.begin() + middle, all.end());
  }
  all.erase(std::unique(all.begin(), all.end()), all.end());
  return all;
}

// Pass 2 of a block: its local corner indices to indices into the whole mesh's keys.
void remapBlock(const std::vector<std::uint64_t>& blockKeys, const std::vector<std::uint64_t>& keys,
                std::vector<std::uint32_t>& remap, std::uint32_t* corners, std::size_t cornerCount) {
  remap.resize(blockKeys.size());
  auto at = keys.begin();
  for (std::size_t i = 0; i < blockKeys.size(); ++i) {
    at = std::lower_bound(at, keys.end(), blockKeys[i]);  // both sorted: each search starts at the last
    remap[i] = static_cast<std::uint32_t>(at - keys.begin());
  }
  for (std::size_t i = 0; i < cornerCount; ++i) corners[i] = remap[corners[i]];
}

// Positions: affine in x and y; z interpolates between the (possibly uneven) layers.
void computePositions(const Grid& grid, const std::vector<std::uint64_t>& keys, std::vector<float>& positions, int threads) {
  positions.resize(3 * keys.size());
  parallelChunks(keys.size(), threads, [&](int, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      const std::uint64_t key = keys[v];
      const double x = static_cast<double>(key & kKeyMask);
      const double y = static_cast<double>((key >> kKeyBits) & kKeyMask);
      const std::uint64_t z = (key >> (2 * kKeyBits)) & kKeyMask;
      const std::size_t layer = static_cast<std::size_t>(z / 12);
      const std::uint64_t frac = z % 12;
      double pz = grid.layerZ[layer];
      if (frac != 0) pz += (grid.layerZ[layer + 1] - grid.layerZ[layer]) * static_cast<double>(frac) / 12.0;
      positions[3 * v] = static_cast<float>(grid.originX + grid.spacingX * x / 12.0);
      positions[3 * v + 1] = static_cast<float>(grid.originY + grid.spacingY * y / 12.0);
      positions[3 * v + 2] = static_cast<float>(pz);
    }
  });
}

}  // namespace

MultiLabelMesh assembleMesh(const Grid& grid, std::span<const CellCase> cases, int threads) {
  MultiLabelMesh mesh;
  if (cases.empty() || grid.nx < 2 || grid.ny < 2) return mesh;
  const CaseTable& table = caseTable();
  const Blocks blocks = planBlocks(table, cases, threads);
  const std::size_t triangleCount = blocks.firstTriangle.back();
  mesh.labels.resize(2 * triangleCount);
  mesh.triangles.resize(3 * triangleCount);
  std::vector<std::vector<std::uint64_t>> blockKeys(blocks.count);
  parallelChunks(blocks.count, threads, [&](int, std::size_t b0, std::size_t b1) {
    std::vector<std::uint64_t> keys;  // reused by the thread's blocks
    IndexScratch scratch;
    for (std::size_t b = b0; b < b1; ++b) {
      const std::size_t first = blocks.firstTriangle[b];
      emitTriangles(table, grid, blocks.cases(cases, b), blocks.firstTriangle[b + 1] - first, keys,
                    mesh.labels.data() + 2 * first);
      blockKeys[b] = indexBlock(keys, scratch, mesh.triangles.data() + 3 * first);
    }
  });
  mesh.keys = mergeKeys(blockKeys);
  parallelChunks(blocks.count, threads, [&](int, std::size_t b0, std::size_t b1) {
    std::vector<std::uint32_t> remap;
    for (std::size_t b = b0; b < b1; ++b) {
      const std::size_t first = blocks.firstTriangle[b];
      remapBlock(blockKeys[b], mesh.keys, remap, mesh.triangles.data() + 3 * first, 3 * (blocks.firstTriangle[b + 1] - first));
      std::vector<std::uint64_t>().swap(blockKeys[b]);
    }
  });
  computePositions(grid, mesh.keys, mesh.positions, threads);
  return mesh;
}

}  // namespace scansurf
