// scansurf: IMOD binary model input (IMOD's "binary model file format", Version 1,
// Revision 2: big-endian chunks 'IMOD' 'V1.2', a 232-byte model header, then per object an
// 'OBJT' chunk of 176 bytes followed by its 'CONT' and 'MESH' chunks and optional chunks
// (id, 4-byte size, data), ending with 'IEOF').
//
// Each closed object (object flag bit 3 "open" and bit 9 "scattered" off) becomes a feature
// named by the object (or "object N" when unnamed) in its colour; its closed contours
// (contour flag bit 3 off) are grouped by z. Points are stored in image pixels; the reader
// scales them to model units: (x * xscale, y * yscale, z * zscale) * pixsize, in the units
// of the header (-6 microns, -9 nm, ...; 0 pixels). Open objects, scattered-point objects and
// open contours are skipped with a warning; a closed contour whose points leave one z plane
// is an error. Meshes and unknown chunks are skipped by their size.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "scansurf/contours.h"
#include "scansurf/input.h"
#include "scansurf/result.h"

namespace scansurf {

struct ImodOptions {
  std::vector<std::string> objectPatterns;  // glob, case-insensitive; empty = every object
  bool requireFeatures = true;              // false: nothing to surface is not an error (listing)
  // Points of one contour may differ in z by this much (image pixels, before zscale).
  double planeTolerance = 1e-3;
};

struct ImodModel {
  ContourSet contours;              // validated; in model units
  std::vector<ObjectInfo> objects;  // in model order, numbered from 1
  std::string name;                 // the model's name field
  double pixelSize = 1;             // pixsize
  double scale[3] = {1, 1, 1};      // xscale, yscale, zscale
  int unitsCode = 0;                // units field
};

// Reads an IMOD binary model. Errors name the file and, where it applies, the object (number
// and name) and contour (number, from 1): Errc::Io (cannot read), Errc::InvalidInput (not an
// IMOD model, an unsupported version, a truncated file or chunk with the byte offset, a
// negative count, a non-positive pixel size or scale, a non-planar closed contour),
// Errc::InvalidArgument (an object pattern that matches nothing).
Result<ImodModel> readImodModel(const std::filesystem::path& path, const ImodOptions& options = {});

// True when the file starts with the IMOD model id "IMOD".
bool hasImodMagic(const std::filesystem::path& path);

// The unit name of IMOD's units code ("µm" for -6, "pixels" for 0, ...); empty when unknown.
std::string imodUnitName(int code);

}  // namespace scansurf
