// scansurf tests: deterministic contour sets of known shape, all in mm. Every generator
// returns a ContourSet whose source is the shape's name; slices use z = c ± (k + 0.5) * spacing
// unless said otherwise. Circles get 4 * ceil(radius * 8) vertices (at least 16) by default.
#pragma once

#include <cstdint>
#include <string>

#include "scansurf/contours.h"

namespace scansurf {

// Counter-clockwise circle polygon; vertices = 0 picks the default count above.
Contour circleContour(Point2 centre, double radius, int vertices = 0);
// Counter-clockwise axis-aligned ellipse polygon.
Contour ellipseContour(Point2 centre, double radiusX, double radiusY, int vertices);

// One feature "sphere": every slice plane z = centreZ ± (k + 0.5) * sliceSpacing that cuts it.
ContourSet sphereContours(double radius, double sliceSpacing, Point2 centre = {}, double centreZ = 0);

// One feature "torus", axis along z (a ring lying in the xy plane), major radius R, tube radius
// r < R: each slice is an annulus, outer circle plus a hole. Genus 1.
ContourSet torusContours(double majorRadius, double tubeRadius, double sliceSpacing);

// The same torus turned by `tiltDegrees` about the x axis: near its middle a slice is two nested
// loops, higher and lower two crescents or one arc. Genus 1.
ContourSet tiltedTorusContours(double majorRadius, double tubeRadius, double tiltDegrees, double sliceSpacing);

// One feature "vessel" shaped like trousers: a trunk circle on `trunkSlices` slices, then two
// branch circles (overlapping the trunk in xy, so they connect) on `branchSlices` slices.
// Slices at z = (k + 0.5) * sliceSpacing, k = 0 .. trunkSlices + branchSlices - 1.
ContourSet yBranchContours(double trunkRadius = 6, double branchOffset = 5, double branchRadius = 3, double sliceSpacing = 2,
                           int trunkSlices = 5, int branchSlices = 5);

// Features "outer" (sphere of outerRadius) and "inner" (sphere of innerRadius, same centre).
ContourSet nestedSpheresContours(double outerRadius = 20, double innerRadius = 8, double sliceSpacing = 2.5);

// Features "left" and "right": the two halves of a cylinder of `radius` split by the plane
// x = 0, on `slices` slices; both contain the identical shared polyline along x = 0.
ContourSet abuttingContours(double radius = 10, int slices = 6, double sliceSpacing = 2.5);

// Features "a" and "b": two thin bars `width` mm across (ellipses of half-width width / 2 and
// half-length 10 - k on slice k), centres 3.2 mm apart, on five slices 2 mm apart from z = 0.
ContourSet thinBarsContours(double width);

// Features "a", "b" and "c": three sectors of a disc of radius 8 on six slices 2 mm apart,
// meeting along the cylinder's axis (off the pixel lattice): junction curves where the three
// meet and where two of them meet the background.
ContourSet threeSectorsContours();

// The bundled demo: BODY (ellipse skin), abutting "prostate" and "rectum", "target" nested in
// the prostate, a branching "vessel", and a "vertebra" that is ring-shaped on its middle
// slices; 40 slices at 2.5 mm, about 1 mm between contour points, coordinates rounded to 0.01.
// Another slice spacing gives the same shapes cut over the same 100 mm.
ContourSet phantomContours(double sliceSpacing = 2.5);

// Rounds every coordinate to a multiple of step and drops points that became repeats.
void roundCoordinates(ContourSet& contours, double step);

// A small deterministic generator (splitmix64), the same on every platform.
class ShapeRng {
 public:
  explicit ShapeRng(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next();
  double uniform(double lo, double hi);  // [lo, hi)

 private:
  std::uint64_t state_;
};

// A star-shaped simple polygon around centre: `vertices` points at increasing angles, radii
// uniform in [minRadius, maxRadius].
Contour randomPolygon(ShapeRng& rng, Point2 centre, double minRadius, double maxRadius, int vertices);

}  // namespace scansurf
