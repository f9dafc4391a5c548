// scansurf CLI: the command line, parsed into one struct (CLI11 does the parsing; no number
// parsing here can throw).
#pragma once

#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "scansurf/engine.h"
#include "scansurf/input.h"
#include "scansurf/outputs.h"
#include "scansurf/preview.h"
#include "scansurf/report.h"

namespace scansurf::cli {

struct CliOptions {
  std::vector<std::string> commandLine;  // argv as given, for the report
  std::string input;
  std::string output;  // a directory, or NAME.glb
  bool listRois = false;
  bool listObjects = false;
  bool listOverlaps = false;
  bool quiet = false;
  bool jsonProgress = false;
  EngineOptions engine;
  BuildOptions build = BuildOptions::recommended();  // the flags below change it
  ReadOptions read;
  std::vector<std::string> formats;  // --format, before parsing into MeshFormat
  SceneOptions scene;
  std::string labelVolume, dicomSeg, report, preview;
  std::string volumeUnit = "input";  // of the summary's and the report's volumes (volumeUnitFor)
  std::string view = "oblique";
  std::vector<unsigned> previewSize;
};

// What parseCommandLine decided: run with `options`, or exit at once with `exitCode` (help,
// --version, or a usage error, already printed).
struct ParsedCommandLine {
  bool run = false;
  int exitCode = 0;
  CliOptions options;
};

ParsedCommandLine parseCommandLine(int argc, char** argv);

}  // namespace scansurf::cli
