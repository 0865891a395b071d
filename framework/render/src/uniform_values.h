// Sets lab.json uniform values on a linked program, typed by what the program declares: a JSON
// number becomes a float, int or uint; an array a vector, matrix (column-major, flat or as
// columns) or array; an object a struct's members ("lights[1].color"); "@pass.view_projection"
// the matrix of another pass's camera. A value that does not fit the declared type is an error
// naming the lab.json key, never a silent zero.
#pragma once

#include <functional>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "shaderlab/lab/lab_spec.h"
#include "shaderlab/render/shader_program.h"

namespace shaderlab {

// The camera of a pass, for "@pass.view" and friends.
struct PassCameraValues {
    glm::mat4 view{1.0f}, projection{1.0f};
    glm::vec3 position{0.0f};
};
using PassCameraLookup = std::function<const PassCameraValues*(const std::string& pass)>;

struct UniformApplyResult {
    bool declared = true;  // false: the program has no active uniform of that name
    std::string error;     // "" when applied; else "<path>: <problem>"
};

// The program must be current (glUseProgram).
UniformApplyResult applyUniform(const ShaderProgram& program, const UniformSetting& setting,
                                const PassCameraLookup& cameras);

// Whether `name` appears as an identifier in GLSL text (comments not excluded): a uniform the lab
// sets that is nowhere in the source is likely misspelt; one that is there but inactive is not.
bool mentionsIdentifier(const std::string& text, const std::string& name);
// Names declared with `uniform` in GLSL text, for "did you mean" suggestions.
std::vector<std::string> declaredUniformNames(const std::string& text);

}  // namespace shaderlab
