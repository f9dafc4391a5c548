// scansurf CLI: the command line, parsed with CLI11 into CliOptions (see options.h).
#include "options.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <utility>
#include <vector>

#include "help_format.h"
#include "scansurf/version.h"

namespace scansurf::cli {
namespace {

constexpr const char* kFooter =
    "Outputs: OUTDIR/<feature>.ply (one closed surface per feature, outward) and OUTDIR/multilabel.ply (every "
    "separating surface, each face with its two labels; label = feature index + 1); other formats with --format; "
    "-o NAME.glb writes one Draco-compressed glTF scene instead; -o NAME.ply or .vtp one file with the "
    "multi-label mesh, -o NAME.stl, .obj or .drc one file with every closed surface; --label-volume and "
    "--dicom-seg write the label volume.\n"
    "Many inputs: scansurf batch INPUT... -o OUT (scansurf batch --help).\n"
    "Exit codes: 0 ok, 2 usage, 3 invalid input, 4 I/O, 5 no Vulkan device, 6 Vulkan failure, 7 internal, 8 out "
    "of memory, 9 over --max-memory, 10 defective surface (docs/limits.md).\n"
    "Environment: SCANSURF_DEVICE, SCANSURF_VALIDATION=1, SCANSURF_THREADS.";

// What --help shows for each option's value.
constexpr std::pair<const char*, const char*> kValueNames[] = {
    {"--output", "OUTDIR"},
    {"--voxel-size", "S"},
    {"--grid", "NX NY"},
    {"--convention", "C"},
    {"--overlaps", "M"},
    {"--overlap-tolerance", "T"},
    {"--device", "D"},
    {"--threads", "N"},
    {"--max-memory", "SIZE"},
    {"--long-gap", "F"},
    {"--interpolate", "I"},
    {"--caps", "C"},
    {"--smooth-iterations", "N"},
    {"--smooth-strength", "X"},
    {"--min-angle", "DEG"},
    {"--snap", "F"},
    {"--simplify-tolerance", "X"},
    {"--simplify-edge-length", "X"},
    {"--simplify-min-angle", "DEG"},
    {"--edge-length", "L"},
    {"--roi", "PATTERN"},
    {"--reference", "DIR"},
    {"--object", "PATTERN"},
    {"--format", "LIST"},
    {"--gltf-frame", "F"},
    {"--draco-bits", "N"},
    {"--draco-level", "N"},
    {"--label-volume", "F"},
    {"--dicom-seg", "F.dcm"},
    {"--report", "F.json"},
    {"--volume-unit", "U"},
    {"--preview", "F.png"},
    {"--view", "V"},
    {"--preview-size", "W H"},
};

// A finite number with lo < value <= hi (lo < value when openLow, else lo <= value), parsed
// without throwing; the message prints the bounds readably (no 309-digit DBL_MAX).
CLI::Validator numberIn(double lo, double hi, bool openLow, const std::string& description) {
  return CLI::Validator(
      [=](std::string& text) {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        const bool ok = end != text.c_str() && *end == '\0' && std::isfinite(v) && (openLow ? v > lo : v >= lo) && v <= hi;
        return ok ? std::string() : "'" + text + "' is not " + description;
      },
      description);
}

// A memory size: a number with an optional binary unit, K, M, G or T (KiB, MiB, GiB, TiB; "B",
// "iB" and lower case accepted): "8G", "1.5GiB", "512m". Zero or less, or beyond 1 EiB: nullopt.
std::optional<std::uint64_t> parseMemorySize(const std::string& text) {
  char* end = nullptr;
  const double number = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || !std::isfinite(number) || number <= 0) return std::nullopt;
  std::string unit(end);
  for (char& c : unit) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  for (const char* suffix : {"IB", "B"})
    if (unit.size() > std::strlen(suffix) && unit.ends_with(suffix)) unit.resize(unit.size() - std::strlen(suffix));
  const std::string units = "KMGT";
  double scale = 1;
  if (unit.size() == 1 && units.find(unit[0]) != std::string::npos)
    scale = std::ldexp(1.0, 10 * (1 + static_cast<int>(units.find(unit[0]))));
  else if (!unit.empty() && unit != "B")
    return std::nullopt;
  const double bytes = number * scale;
  if (bytes < 1 || bytes > std::ldexp(1.0, 60)) return std::nullopt;
  return static_cast<std::uint64_t>(bytes);
}

// "auto", "off", "DEPTH" or "DEPTH,PERCENT" (DEPTH a positive length or "auto", PERCENT in [0, 100]).
std::optional<OverlapTolerance> parseOverlapTolerance(const std::string& text) {
  OverlapTolerance t;
  if (text == "auto") return t;
  if (text == "off") {
    t.enabled = false;
    return t;
  }
  const std::size_t comma = text.find(',');
  const std::string depth = text.substr(0, comma);
  const auto number = [](const std::string& s, double& out) {
    if (s.empty()) return false;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    return ec == std::errc() && end == s.data() + s.size() && std::isfinite(out);
  };
  if (depth != "auto" && !(number(depth, t.depth) && t.depth > 0)) return std::nullopt;
  if (comma != std::string::npos && !(number(text.substr(comma + 1), t.percent) && t.percent >= 0 && t.percent <= 100))
    return std::nullopt;
  return t;
}

// Local flags the struct does not hold directly.
struct Flags {
  std::vector<int> grid;
  std::string convention = "enclosing";
  std::string overlaps = "layers";
  std::string overlapTolerance = "auto";
  bool noSmooth = false, noContourFit = false, noJunctions = false, noKeepVolumes = false, noDraco = false;
  bool remesh = false, noCurvatureSizing = false;
  std::string reference;
  std::string gltfFrame = "gltf";
  std::string maxMemory;
  std::string interpolate = "auto", caps = "round";
};

void addGeneral(CLI::App& app, CliOptions& o, Flags& f) {
  app.add_option("input", o.input,
                 "contour set, recognised by content: JSON (docs/input-format.md), DICOM RTSTRUCT, Reconstruct series "
                 "(.ser or one of its section files), IMOD model (.mod)")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("-o,--output", o.output,
                 "output directory (created if missing), or one file: NAME.glb, .ply, .vtp, .stl, .obj, .drc; required unless "
                 "--list-rois, --list-objects or --list-overlaps");
  auto* voxel =
      app.add_option("--voxel-size", o.build.grid.voxelSize,
                     "in-plane pixel size, input units (default: the reference CT's with --reference, else 256 pixels along "
                     "the longer side of every structure in the file, selected or not)")
          ->check(numberIn(0, 1e9, true, "a positive, finite number"));
  app.add_option("--grid", f.grid, "pixels along x and y including the 1-pixel border (4 to 16384 each)")
      ->expected(2)
      ->check(CLI::Range(4, 16384))
      ->excludes(voxel);
  app.add_option("--convention", f.convention,
                 "enclosing: each surface around all its contours enclose, nested features included; "
                 "partition: the boundary of the region each feature owns")
      ->check(CLI::IsMember({"enclosing", "partition"}))
      ->capture_default_str();
  app.add_option("--overlaps", f.overlaps,
                 "layers: partly overlapping features are surfaced in separate layers, each keeping its own region; "
                 "partition: one label per voxel, higher priority wins (reports what each feature lost)")
      ->check(CLI::IsMember({"layers", "partition"}))
      ->capture_default_str();
  app.add_option("--overlap-tolerance", f.overlapTolerance,
                 "which partial overlaps are incidental slivers between neighbours (one layer, shared voxels split "
                 "down the middle) rather than by design (separate layers): DEPTH[,PERCENT] - every shared voxel "
                 "within DEPTH (input units) of the nearer outline and the shared volume at most PERCENT of the "
                 "smaller structure; auto = 2 pixels or half the slice spacing (the larger), 2 %; off = every "
                 "shared voxel means layers")
      ->check(CLI::Validator(
          [](std::string& text) {
            return parseOverlapTolerance(text) ? std::string() : "'" + text + "' is not auto, off or DEPTH[,PERCENT]";
          },
          "auto|off|DEPTH[,PERCENT]"))
      ->capture_default_str();
  app.add_flag("--list-overlaps", o.listOverlaps,
               "list the pairs of structures that share voxels (shared volume, depth, verdict) without surfacing, and exit");
  app.add_option("--device", o.engine.device, "Vulkan device: index or part of its name (default: best; env SCANSURF_DEVICE)");
  app.add_flag("--validation", o.engine.validation, "enable the Vulkan validation layers");
  app.add_option("--threads", o.build.threads,
                 "CPU threads for the stages on the CPU, assembly to simplification, and statistics (default and "
                 "at most: the machine's cores)")
      ->check(CLI::Range(0, BuildOptions::kMostThreads));
  app.add_option("--max-memory", f.maxMemory,
                 "host memory the run may use, e.g. 8G or 512M (default: what the machine has available); a run that "
                 "would need more is refused before it starts (exit 9)")
      ->check(CLI::Validator(
          [](std::string& text) {
            return parseMemorySize(text) ? std::string() : "'" + text + "' is not a memory size such as 8G or 512M";
          },
          "SIZE"));
  app.add_flag("--keep-defective", o.build.audit.keepDefective,
               "write a surface the audit finds open, not manifold or not oriented (for debugging; still exit 10)");
  app.add_flag("-q,--quiet", o.quiet, "print errors and warnings only");
  app.add_flag("--json-progress", o.jsonProgress, "progress as JSON lines on stderr, for scripts");
}

void addSmoothing(CLI::App& app, CliOptions& o, Flags& f) {
  SmoothingOptions& s = o.build.smoothing;
  app.add_flag("--no-smooth", f.noSmooth, "write the raw (staircase) separating surfaces, without smoothing");
  app.add_option("--smooth-iterations", s.iterations, "how much to smooth, in plain relaxation sweeps (run as fewer super-steps)")
      ->check(CLI::Range(1, SmoothingOptions::kMostIterations))
      ->capture_default_str();
  app.add_option("--smooth-strength", s.strength, "step of each smoothing sweep, in (0, 1]")
      ->check(numberIn(0, 1, true, "a number in (0, 1]"))
      ->capture_default_str();
  app.add_flag("--no-contour-fit", f.noContourFit, "do not place contour-plane vertices on the original contours");
  app.add_flag("--no-junction-smoothing", f.noJunctions, "keep vertices where three or more structures meet in place");
  app.add_flag("--no-keep-volume", f.noKeepVolumes,
               "leave each structure's volume as relaxation made it (default: restored to its contours' slab volume)");
  app.add_option("--min-angle", s.minAngle,
                 "smallest triangle angle, degrees, that placing and smoothing vertices may leave (moves that would make a "
                 "sharper triangle are shortened; costs accuracy, see docs/method.md \"Triangle shape\"); default 0: off")
      ->check(CLI::Range(0.0, 30.0))
      ->capture_default_str();
  app.add_option("--snap", s.snap,
                 "merge the vertices crowding a voxel centre into it when one lies within this fraction of its lattice "
                 "edge of it (removes slivers; scaled down where the slices lie closer than two pixels; docs/method.md "
                 "\"Triangle shape\"); 0: off")
      ->check(numberIn(0, 0.45, false, "a number in [0, 0.45]"))
      ->capture_default_str();
}

// "auto", "off" or a whole number of layers per gap, 1 to kMaxFactor.
std::optional<int> parseInterpolation(const std::string& text) {
  if (text == "auto") return InterpolationOptions::kAuto;
  if (text == "off") return 1;
  int n = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
  if (ec != std::errc() || end != text.data() + text.size() || n < 1 || n > InterpolationOptions::kMaxFactor) return std::nullopt;
  return n;
}

void addInterpolation(CLI::App& app, CliOptions& o, Flags& f) {
  app.add_option("--long-gap", o.build.grid.gapFactor,
                 "a structure's consecutive planes more than F times its median spacing apart are capped on each side, "
                 "not bridged (0: bridge every gap)")
      ->check(CLI::Range(0.0, 1000.0))
      ->capture_default_str();
  app.add_option("--interpolate", f.interpolate,
                 "layers between contour planes, by shape-based interpolation: auto (about one per in-plane pixel in "
                 "gaps of 3 pixels or more, the volume kept under 96 M voxels), off, or N (N-1 layers in every gap, "
                 "N up to 16)")
      ->check(CLI::Validator(
          [](std::string& text) {
            return parseInterpolation(text) ? std::string() : "'" + text + "' is not auto, off or 1 to 16";
          },
          "auto|off|N"))
      ->capture_default_str();
  app.add_option("--caps", f.caps,
                 "how a structure closes beyond its first and last contour (with interpolation): round (a dome 3/4 to 1 "
                 "slice gap high that leaves the last contour at the structure's taper there) or flat (its last contour "
                 "extruded half a gap); both keep the volume planning systems give (the end contour's area times half the gap)")
      ->check(CLI::IsMember({"round", "flat"}))
      ->capture_default_str();
}

void addSimplification(CLI::App& app, CliOptions& o) {
  SimplificationOptions& s = o.build.simplification;
  app.add_flag("--simplify,!--no-simplify", s.enabled,
               "merge the smoothed surfaces' triangles into fewer, better-shaped ones, every contour-plane cross-section "
               "and junction curve kept (default: on; on the benchmark sets it leaves about 0.7 of the triangles, under "
               "the 3D Slicer route's count, for about 3 to 4 times smoothing's time; --no-simplify skips it; see "
               "docs/method.md \"Simplification\")");
  app.add_option("--simplify-tolerance", s.tolerance, "how far simplification may move the surface, in-plane voxels")
      ->check(numberIn(0, SimplificationOptions::kMostTolerance, true, "a number in (0, 0.5]"))
      ->capture_default_str();
  app.add_option("--simplify-edge-length", s.edgeLength, "edge length simplification stops at, in-plane voxels")
      ->check(CLI::Range(SimplificationOptions::kLeastEdge, SimplificationOptions::kMostEdge))
      ->capture_default_str();
  app.add_option("--simplify-min-angle", s.minAngle,
                 "smallest angle, degrees, below which simplification never makes a triangle sharper than those it replaces")
      ->check(CLI::Range(0.0, 30.0))
      ->capture_default_str();
}

void addRemeshing(CLI::App& app, CliOptions& o, Flags& f) {
  app.add_flag("--remesh,!--no-remesh", f.remesh,
               "remesh the smoothed surfaces into well-shaped triangles of about --edge-length (default: off; "
               "it takes minutes on a million triangles, see docs/method.md \"Remeshing\")");
  app.add_option("--edge-length", o.build.remeshing.edgeLength,
                 "remeshing's target edge length, input units (default: 1.15 in-plane voxels or 0.33 slice gaps, the longer)")
      ->check(numberIn(0, 1e9, true, "a positive, finite number"));
  app.add_flag("--no-curvature-sizing", f.noCurvatureSizing,
               "remeshing: one target edge length wherever the surface curves (default: shorter edges where a chord of "
               "--edge-length would stand more than 0.2 voxel inside the surface)");
}

void addDicom(CLI::App& app, CliOptions& o, Flags& f) {
  app.add_option("--roi", o.read.roiPatterns,
                 "RTSTRUCT, Slicer segmentation: surface only the ROIs (segments) whose name matches (glob, "
                 "case-insensitive; repeatable)")
      ->expected(1)
      ->take_all();
  app.add_flag("--list-rois", o.listRois, "RTSTRUCT, Slicer segmentation: list the file's ROIs (segments) and exit");
  app.add_option("--reference", f.reference, "RTSTRUCT: folder of a CT series; the label volume lies on its voxel grid");
}

void addOutputs(CLI::App& app, CliOptions& o, Flags& f) {
  DracoOptions& draco = o.scene.dracoOptions;
  app.add_option("--format", o.formats,
                 "per-feature formats in OUTDIR: ply (default, with multilabel.ply), drc, obj, stl, vtp (with "
                 "multilabel.vtp); scenes: glb (OUTDIR/<input name>.glb), seg.vtm (3D Slicer's closed-surface "
                 "segmentation OUTDIR/<input name>.seg.vtm with one .vtp per segment); comma-separated")
      ->delimiter(',');
  app.add_flag("--no-draco", f.noDraco, "GLB without KHR_draco_mesh_compression (plain float accessors)");
  app.add_option("--gltf-frame", f.gltfFrame,
                 "GLB coordinates: gltf (a root node turns patient LPS into glTF's y-up "
                 "metres) or patient (raw input coordinates)")
      ->check(CLI::IsMember({"gltf", "patient"}))
      ->capture_default_str();
  app.add_option("--draco-bits", draco.quantizationBits, "Draco position quantization bits (default: error below 1/25 voxel)")
      ->check(CLI::Range(1, 30));
  app.add_option("--draco-level", draco.compressionLevel, "Draco compression level, 0 fastest .. 10 smallest")
      ->check(CLI::Range(0, 10))
      ->capture_default_str();
  app.add_option("--label-volume", o.labelVolume,
                 "write the label volume by extension: .nrrd or .seg.nrrd (LPS; a .seg.nrrd opens as a Slicer "
                 "segmentation) with its label table F.ctbl, or .nii / .nii.gz (NIfTI-1, RAS: x and y negated) "
                 "with an ITK-SNAP label table F.label.txt");
  app.add_option("--dicom-seg", o.dicomSeg,
                 "write the label volume as a DICOM Segmentation (.dcm) on the --reference CT's grid, one segment per "
                 "feature, referencing the CT images");
  app.add_option("--report", o.report, "write a JSON report: per-feature statistics, parameters, device, timings");
  app.add_option("--volume-unit", o.volumeUnit,
                 "unit of the volumes in the summary and the report: input (the input's unit cubed), mm3, cm3 "
                 "(or cc, ml), um3, nm3")
      ->check(CLI::IsMember({"input", "mm3", "cm3", "cc", "ml", "um3", "nm3"}))
      ->capture_default_str();
  app.add_option("--preview", o.preview, "render a picture of the surfaces on the Vulkan device (.png)");
  app.add_option("--view", o.view, "preview camera")
      ->check(CLI::IsMember({"oblique", "front", "back", "left", "right", "top", "bottom"}))
      ->capture_default_str();
  app.add_option("--preview-size", o.previewSize,
                 "preview size in pixels, at most 8192 each (rendered at twice the size; default 960 720)")
      ->expected(2)
      ->check(CLI::Range(1, 8192));
}

void addObjects(CLI::App& app, CliOptions& o) {
  app.add_option("--object", o.read.objectPatterns,
                 "Reconstruct, IMOD: surface only the objects whose name matches (glob, case-insensitive; repeatable)")
      ->expected(1)
      ->take_all();
  app.add_flag("--list-objects", o.listObjects, "Reconstruct, IMOD: list the file's objects and exit");
}

// Moves the flags into the options struct.
void apply(const Flags& f, CliOptions& o) {
  if (f.grid.size() == 2) o.build.grid.nx = f.grid[0], o.build.grid.ny = f.grid[1];
  o.build.convention = f.convention == "partition" ? SurfaceConvention::Partition : SurfaceConvention::Enclosing;
  o.build.overlaps = *parseOverlapMode(f.overlaps);
  o.build.overlapTolerance = *parseOverlapTolerance(f.overlapTolerance);
  o.build.interpolation.factor = *parseInterpolation(f.interpolate);
  o.build.interpolation.caps = f.caps == "flat" ? CapShape::Flat : CapShape::Round;
  o.build.smoothing.enabled = !f.noSmooth;
  o.build.smoothing.contourFit = !f.noContourFit;
  o.build.smoothing.junctions = !f.noJunctions;
  o.build.smoothing.keepVolumes = !f.noKeepVolumes;
  o.build.remeshing.enabled = f.remesh;
  o.build.remeshing.curvatureSizing = !f.noCurvatureSizing;
  o.scene.draco = !f.noDraco;
  o.scene.frame = f.gltfFrame == "patient" ? SceneFrame::Patient : SceneFrame::Gltf;
  o.read.referenceSeries = f.reference;
  if (!f.maxMemory.empty()) o.build.memoryLimit = *parseMemorySize(f.maxMemory);
  if (!o.preview.empty()) {  // in the budget from the start: refused before the work, not after
    PreviewOptions picture;
    if (o.previewSize.size() == 2) picture.width = o.previewSize[0], picture.height = o.previewSize[1];
    o.build.reservedMemory = estimatePreviewBytes(picture);
  }
  // More threads than cores only costs memory and switches (results do not depend on it).
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  o.build.threads = std::min(o.build.threads, cores);
}

// Edit distance between two option names (insertions, deletions, substitutions).
std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// The option nearest an unknown "--name" (at most a third of its letters off), or "".
std::string nearestOption(const CLI::App& app, const std::string& given) {
  const std::string name = given.substr(0, given.find('='));
  std::string best;
  std::size_t bestDistance = std::max<std::size_t>(1, name.size() / 3) + 1;
  for (const CLI::Option* option : app.get_options())
    for (const std::string& longName : option->get_lnames()) {
      const std::size_t d = editDistance(name, "--" + longName);
      if (d < bestDistance) bestDistance = d, best = "--" + longName;
    }
  return best;
}

// A usage error a person can act on: an unknown option with the one meant, a missing input as
// the I/O error it is (exit 4); CLI11's own message otherwise.
int usageError(const CLI::App& app, const CLI::ParseError& e) {
  if (dynamic_cast<const CLI::ExtrasError*>(&e)) {
    for (const std::string& arg : app.remaining())
      if (arg.rfind("--", 0) == 0) {
        const std::string meant = nearestOption(app, arg);
        std::fprintf(stderr, "scansurf: error: unknown option %s%s%s (scansurf --help lists them)\n", arg.c_str(),
                     meant.empty() ? "" : "; did you mean ", meant.c_str());
        return 2;
      }
  }
  // CLI11 refuses a missing input before assigning it: the path is in its message.
  static constexpr std::string_view kMissing = "File does not exist: ";
  const std::string what = e.what();
  if (const auto at = what.find(kMissing); dynamic_cast<const CLI::ValidationError*>(&e) && at != std::string::npos) {
    std::fprintf(stderr, "scansurf: error: cannot read '%s': no such file\n", what.substr(at + kMissing.size()).c_str());
    return 4;
  }
  const int code = app.exit(e);
  return code == 0 ? 0 : 2;
}

}  // namespace

ParsedCommandLine parseCommandLine(int argc, char** argv) {
  CLI::App app{"scansurf: separating surfaces from planar contours (scanline surfacing on Vulkan)", "scansurf"};
  useHelpLayout(app);
  app.footer(kFooter);
  app.set_version_flag("--version", std::string("scansurf ") + version());
  ParsedCommandLine parsed;
  parsed.options.commandLine.assign(argv, argv + argc);
  Flags flags;
  const auto group = [&](const char* name) { app.option_defaults()->group(name); };
  group("Options");
  addGeneral(app, parsed.options, flags);
  group("Between the slices (docs/method.md)");
  addInterpolation(app, parsed.options, flags);
  group("Smoothing, on by default (docs/method.md)");
  addSmoothing(app, parsed.options, flags);
  group("Simplification, on by default (docs/method.md)");
  addSimplification(app, parsed.options);
  group("Remeshing, off by default (docs/method.md)");
  addRemeshing(app, parsed.options, flags);
  group("Inputs (docs/formats.md)");
  addDicom(app, parsed.options, flags);
  addObjects(app, parsed.options);
  group("Outputs (docs/outputs.md)");
  addOutputs(app, parsed.options, flags);
  for (const auto& [name, value] : kValueNames) app.get_option(name)->option_text(value);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    parsed.exitCode = usageError(app, e);
    return parsed;
  }
  apply(flags, parsed.options);
  parsed.run = true;
  return parsed;
}

}  // namespace scansurf::cli
