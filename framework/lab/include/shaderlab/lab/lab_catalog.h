// Finds labs: every folder directly under the labs root that holds a lab.json, in name order,
// so the list of labs is the folders themselves and cannot drift from them.
#pragma once

#include <string>
#include <vector>

namespace shaderlab {

std::vector<std::string> listLabIds(const std::string& labs_root);

}  // namespace shaderlab
