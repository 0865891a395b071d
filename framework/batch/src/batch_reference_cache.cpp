// Reference renders kept between runs: the key of an entry, and making one; see
// reference_cache.h.
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <vector>

#include "batch_detail.h"
#include "shaderlab/base/timings.h"
#include "shaderlab/batch/reference_cache.h"
#include "shaderlab/batch/workers.h"
#include "shaderlab/grading/grading.h"
#include "shaderlab/lab/lab_catalog.h"

namespace fs = std::filesystem;

namespace shaderlab::batch {

void addReferenceInputs(Hasher* h, const std::string& tool_version, const std::string& exe,
                        const std::string& backend, const std::string& renderer, const std::string& labs_root,
                        const std::string& lab_id, const std::string& reference_root) {
    std::error_code ec;
    h->add(tool_version);
    // The version names a release, not a build: the file's size and time tell builds apart.
    struct stat st {};
    if (!exe.empty() && ::stat(exe.c_str(), &st) == 0) {
        h->addNumber(static_cast<std::uint64_t>(st.st_size));
        h->addNumber(static_cast<std::uint64_t>(st.st_mtim.tv_sec));
        h->addNumber(static_cast<std::uint64_t>(st.st_mtim.tv_nsec));
    }
    h->add(backend);
    h->add(renderer);
    h->add(lab_id);
    const bool has_reference =
        !reference_root.empty() && fs::is_directory(fs::path(reference_root) / lab_id, ec);
    h->addTree((fs::path(labs_root) / lab_id).string(), labs_root,
               has_reference ? std::vector<std::string>{"golden"} : std::vector<std::string>{});
    // The folders beside the labs that are not labs (scenes, textures, shared GLSL).
    const std::vector<std::string> ids = listLabIds(labs_root);
    std::vector<std::string> shared;
    for (const fs::directory_entry& e : fs::directory_iterator(labs_root, ec))
        if (e.is_directory(ec) &&
            std::find(ids.begin(), ids.end(), e.path().filename().string()) == ids.end())
            shared.push_back(e.path().string());
    std::sort(shared.begin(), shared.end());
    for (const std::string& d : shared) h->addTree(d, labs_root);
    if (has_reference) {
        h->add("reference");
        h->addTree((fs::path(reference_root) / lab_id).string(), reference_root);
    }
}

namespace {

// Keeps the `keep` newest entries of the lab (by the time they were made), removing the others:
// a cache follows a reference solution as it changes without growing for ever.
void prune(const fs::path& dir, const std::string& lab_id, int keep) {
    std::error_code ec;
    std::vector<std::pair<fs::file_time_type, fs::path>> entries;
    const std::string prefix = lab_id + "-";
    for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
        const std::string name = e.path().filename().string();
        // <lab>-<16 hex digits>; a temporary folder has more after it and is not touched.
        if (name.size() != prefix.size() + 16 || name.compare(0, prefix.size(), prefix) != 0) continue;
        entries.push_back({e.last_write_time(ec), e.path()});
    }
    if (static_cast<int>(entries.size()) <= keep) return;
    std::sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    for (std::size_t i = static_cast<std::size_t>(std::max(keep, 0)); i < entries.size(); ++i)
        fs::remove_all(entries[i].second, ec);
}

}  // namespace

namespace {

fs::path entryFor(const ReferenceCacheSettings& settings, const std::string& lab_id,
                  const std::string& renderer) {
    Hasher key;
    addReferenceInputs(&key, settings.tool_version, selfExe(), backendName(settings.backend), renderer,
                       settings.labs_root, lab_id, settings.reference_root);
    return fs::path(settings.dir) / (lab_id + "-" + key.hex());
}

// The renderer the cache was last asked for with this backend, one file per backend.
fs::path lastRendererFile(const ReferenceCacheSettings& settings) {
    return fs::path(settings.dir) / (std::string("last-renderer-") + backendName(settings.backend) + ".txt");
}

void rememberRenderer(const ReferenceCacheSettings& settings, const std::string& renderer) {
    const fs::path file = lastRendererFile(settings);
    if (batch_detail::readText(file.string(), 4096) == renderer) return;
    std::string ignored;  // only a guess is lost
    writeFileAtomically(file.string(), renderer, &ignored);
}

}  // namespace

std::string guessCachedReference(const ReferenceCacheSettings& settings, const std::string& lab_id) {
    std::error_code ec;
    if (settings.reference_root.empty() || !fs::is_directory(fs::path(settings.reference_root) / lab_id, ec))
        return {};
    const std::string renderer = batch_detail::readText(lastRendererFile(settings).string(), 4096);
    if (renderer.empty()) return {};
    const fs::path entry = entryFor(settings, lab_id, renderer);
    return fs::is_directory(entry / lab_id / "golden", ec) ? entry.string() : std::string();
}

std::string cachedReference(const ReferenceCacheSettings& settings, const std::string& lab_id,
                            const std::string& renderer, std::string* error) {
    std::error_code ec;
    if (settings.reference_root.empty() ||
        !fs::is_directory(fs::path(settings.reference_root) / lab_id, ec)) {
        *error = "no reference solution for " + lab_id;
        return {};
    }
    const fs::path dir = settings.dir;
    const fs::path entry = entryFor(settings, lab_id, renderer);
    if (fs::is_directory(entry / lab_id / "golden", ec)) {
        rememberRenderer(settings, renderer);
        return entry.string();
    }

    fs::create_directories(dir, ec);
    if (ec) {
        *error = dir.string() + ": " + ec.message();
        return {};
    }
    const fs::path tmp = entry.string() + ".tmp-" + std::to_string(getpid());
    fs::remove_all(tmp, ec);
    ScopedTiming timing("render_child", lab_id, "reference");
    const std::vector<std::string> errors =
        writeGoldens(settings.reference_root, settings.labs_root, {lab_id}, settings.backend, tmp.string());
    timing.stop();
    if (!errors.empty()) {
        *error = errors.front();
        fs::remove_all(tmp, ec);
        return {};
    }
    const fs::path hints = fs::path(settings.labs_root) / lab_id / "hints";
    if (fs::is_directory(hints, ec)) fs::copy(hints, tmp / lab_id / "hints", fs::copy_options::recursive, ec);
    if (!ec) fs::rename(tmp, entry, ec);
    if (ec) {
        // Another run may have made the same entry meanwhile: then it is there to use.
        fs::remove_all(tmp, ec);
        if (fs::is_directory(entry / lab_id / "golden", ec)) return entry.string();
        *error = entry.string() + ": cannot be made";
        return {};
    }
    prune(dir, lab_id, settings.keep_per_lab);
    rememberRenderer(settings, renderer);
    return entry.string();
}

}  // namespace shaderlab::batch
