// Per-vertex tangents for normal mapping, following the MikkTSpace method of M. S. Mikkelsen,
// "Simulation of Wrinkled Surfaces Revisited", master's thesis, University of Copenhagen, 2008
// (the method glTF 2.0 names for meshes without TANGENT, spec 3.7.2.1).
//
// What it does, as the thesis describes: per triangle, the tangent and bitangent are the
// derivatives of position along u and v (solved from the triangle's edges and texcoord
// differences); at each corner the tangent is projected into the plane of the vertex normal and
// accumulated weighted by the corner's angle, so the result does not depend on how a face is
// split into triangles; the bitangent's sign (w) says whether the texture is mirrored there.
// What it does not: split a shared vertex whose triangles disagree on the sign or whose tangents
// differ sharply (the reference implementation duplicates such vertices); there the averaged
// tangent is used, which can differ from a MikkTSpace baker's along UV-mirror seams.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace shaderlab {

// Tangents (xyz unit and orthogonal to the normal, w = +1 or -1) for an indexed triangle list.
// `texcoords` in the framework's convention (t = 1 - v): the tangent points along +u, and
// cross(normal, tangent.xyz) * w along +t. Vertices no triangle with usable texcoords touches get
// any unit vector orthogonal to their normal, w = +1.
std::vector<glm::vec4> generateTangents(const std::vector<glm::vec3>& positions,
                                        const std::vector<glm::vec3>& normals,
                                        const std::vector<glm::vec2>& texcoords,
                                        const std::vector<std::uint32_t>& indices);

}  // namespace shaderlab
