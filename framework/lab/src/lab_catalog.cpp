#include "shaderlab/lab/lab_catalog.h"

#include <algorithm>
#include <filesystem>
#include <system_error>

namespace shaderlab {

std::vector<std::string> listLabIds(const std::string& labs_root) {
    namespace fs = std::filesystem;
    std::vector<std::string> ids;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(labs_root, ec)) {
        if (entry.is_directory(ec) && fs::is_regular_file(entry.path() / "lab.json", ec))
            ids.push_back(entry.path().filename().string());
    }
    std::sort(ids.begin(), ids.end());
    return ids;
}

}  // namespace shaderlab
