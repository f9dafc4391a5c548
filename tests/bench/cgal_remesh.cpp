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

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "geometry/remesh/remesh_mesh.h"

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;

// Appends the mesh's vertices (xyz) and triangles (3 indices each) to the arrays.
void append(const Mesh& mesh, std::vector<float>& positions, std::vector<std::uint32_t>& triangles) {
  std::vector<std::uint32_t> index(mesh.num_vertices());  // Surface_mesh index -> array index
  for (const auto v : mesh.vertices()) {
    index[v.idx()] = static_cast<std::uint32_t>(positions.size() / 3);
    const auto& p = mesh.point(v);
    for (int k = 0; k < 3; ++k) positions.push_back(static_cast<float>(p[k]));
  }
  for (const auto f : mesh.faces())
    for (const auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) triangles.push_back(index[v.idx()]);
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
    CGAL::Polygon_mesh_processing::isotropic_remeshing(faces(mesh), length, mesh,
                                                       CGAL::parameters::number_of_iterations(iterations));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // The angles as scansurf's report measures them.
  std::vector<float> positions;
  std::vector<std::uint32_t> triangles;
  for (Mesh& mesh : meshes) mesh.collect_garbage(), append(mesh, positions, triangles);
  const scansurf::AngleFigures angles = scansurf::computeAngleFigures(positions, triangles);
  std::printf(
      "{\"seconds\": %.3f, \"surfaces\": %zu, \"triangles_before\": %zu, \"triangles_after\": %zu, \"min_angle\": %.2f, "
      "\"p5_angle\": %.2f}\n",
      seconds, meshes.size(), before, triangles.size() / 3, angles.min, angles.p5);
  return 0;
}
