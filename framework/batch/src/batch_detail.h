// What the batch library's sources share and nobody outside needs: reading a file whole, and
// taking the results folder's state folder (.shaderlab/) for one batch or merge at a time.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

#include "shaderlab/batch/batch.h"

namespace shaderlab::batch_detail {

constexpr const char* kStateDir = ".shaderlab";  // inside the results folder

// The file's first `max_bytes`; empty when it cannot be read.
std::string readText(const std::filesystem::path& p, std::size_t max_bytes = 64u << 20);

// Makes <out>/.shaderlab (refusing a symlink there: everything of ours goes in there, it must be
// ours) and takes its lock. false, with the message, when either fails.
bool lockStateFolder(const std::filesystem::path& out, batch::FolderLock* lock, std::string* error);

}  // namespace shaderlab::batch_detail
