// A reference for remeshing's speed: CGAL's isotropic remeshing (Botsch & Kobbelt 2004, as
// scansurf's; CGAL::Polygon_mesh_processing::isotropic_remeshing) of each structure's smoothed
// surface on its own, with none of scansurf's checks (no crossing, topology or distance
// test, no shared interfaces, no contour planes kept). It says how much of remeshing's time
// the operations themselves take on a mature, serial implementation, against the smoothing
// time the issue sets as the bound.
//
//   cgal_remesh EDGE_LENGTH ITERATIONS SURFACE.ply...
//
// Prints one JSON line: seconds (remeshing only, reading excluded), triangles before and
// after, smallest angle and 5th percentile after. Built only where CGAL is installed
// (libcgal-dev; tests/bench/cgal_reference.sh installs it): not a test dependency.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;

// Every triangle's smallest angle, degrees.
void smallestAngles(const Mesh& mesh, std::vector<double>& out) {
  for (const auto f : mesh.faces()) {
    std::vector<Kernel::Point_3> p;
    for (const auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) p.push_back(mesh.point(v));
    double smallest = 180;
    for (int i = 0; i < 3; ++i) {
      const auto u = p[(i + 1) % 3] - p[i], w = p[(i + 2) % 3] - p[i];
      const double c = (u * w) / std::sqrt(u.squared_length() * w.squared_length());
      smallest = std::min(smallest, std::acos(std::clamp(c, -1.0, 1.0)) * 180 / 3.141592653589793);
    }
    out.push_back(smallest);
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: %s EDGE_LENGTH ITERATIONS SURFACE.ply...\n", argv[0]);
    return 2;
  }
  const double length = std::atof(argv[1]);
  const int iterations = std::atoi(argv[2]);
  std::vector<Mesh> meshes;
  std::size_t before = 0;
  for (int i = 3; i < argc; ++i) {
    Mesh mesh;
    if (!CGAL::IO::read_polygon_mesh(argv[i], mesh) || !CGAL::is_triangle_mesh(mesh)) {
      std::fprintf(stderr, "%s: not a triangle mesh CGAL can read\n", argv[i]);
      return 1;
    }
    before += mesh.number_of_faces();
    meshes.push_back(std::move(mesh));
  }
  const auto start = std::chrono::steady_clock::now();
  for (Mesh& mesh : meshes)
    CGAL::Polygon_mesh_processing::isotropic_remeshing(faces(mesh), length, mesh, CGAL::parameters::number_of_iterations(iterations));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::vector<double> angles;
  std::size_t after = 0;
  for (const Mesh& mesh : meshes) after += mesh.number_of_faces(), smallestAngles(mesh, angles);
  std::sort(angles.begin(), angles.end());
  const double p5 = angles.empty() ? 0 : angles[angles.size() / 20];
  std::printf("{\"seconds\": %.3f, \"surfaces\": %zu, \"triangles_before\": %zu, \"triangles_after\": %zu, \"min_angle\": %.2f, \"p5_angle\": %.2f}\n",
              seconds, meshes.size(), before, after, angles.empty() ? 0 : angles.front(), p5);
  return 0;
}
