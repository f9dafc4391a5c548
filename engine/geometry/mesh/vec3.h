// scansurf: the one 3-vector of the CPU geometry: GLM's double vector, the C++ twin of the
// shaders' GLSL dvec3, with GLM's arithmetic, dot and cross. Indexable (v[0]..v[2]) and
// brace-initialized like the arrays it replaced.
#pragma once

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace scansurf {

using Vec3 = glm::dvec3;

}  // namespace scansurf
