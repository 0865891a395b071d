// Test support for the batch library's tests and the course's batch tests (tests/batch_test.cpp,
// tests/batch_shards_test.cpp): scratch folders, files, commands run, and zips written with
// libarchive, any entry name allowed (the point is to write hostile ones).
#pragma once

#include <archive.h>
#include <archive_entry.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace shaderlab::batch_testing {

namespace fs = std::filesystem;

inline const fs::path kSource = SHADERLAB_SOURCE_DIR;
inline const std::string kLab = "01-phong";

inline fs::path scratch(const std::string& name) {
    const fs::path p =
        fs::temp_directory_path() / ("shaderlab_batch_" + name + "_" + std::to_string(getpid()));
    fs::remove_all(p);
    fs::create_directories(p);
    return p;
}

inline std::string readFile(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

inline void writeFile(const fs::path& p, const std::string& text) {
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
}

// A shell command's exit code and its stdout and stderr together.
struct CommandRun {
    int exit_code = -1;
    std::string output;
};

inline CommandRun runCommand(const std::string& command) {
    CommandRun r;
    FILE* pipe = popen((command + " 2>&1").c_str(), "r");
    if (!pipe) return r;
    char buf[4096];
    while (std::fgets(buf, sizeof buf, pipe)) r.output += buf;
    const int status = pclose(pipe);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

struct ZipEntry {
    std::string name;
    std::string data;
    unsigned type{AE_IFREG};
    std::string link{};  // symlink target
};

// Writes a zip with libarchive, any entry name allowed (the point is to write hostile ones).
inline void writeZip(const fs::path& path, const std::vector<ZipEntry>& entries) {
    archive* a = archive_write_new();
    archive_write_set_format_zip(a);
    ASSERT_EQ(archive_write_open_filename(a, path.c_str()), ARCHIVE_OK);
    for (const ZipEntry& e : entries) {
        archive_entry* entry = archive_entry_new();
        archive_entry_set_pathname_utf8(entry, e.name.c_str());
        archive_entry_set_filetype(entry, e.type);
        archive_entry_set_perm(entry, 0644);
        if (e.type == AE_IFLNK) archive_entry_set_symlink(entry, e.link.c_str());
        archive_entry_set_size(entry, e.type == AE_IFREG ? static_cast<la_int64_t>(e.data.size()) : 0);
        archive_write_header(a, entry);
        if (e.type == AE_IFREG && !e.data.empty()) archive_write_data(a, e.data.data(), e.data.size());
        archive_entry_free(entry);
    }
    archive_write_close(a);
    archive_write_free(a);
}

// A zip of one empty entry whose Unix mode (in the central directory's external attributes) is
// `mode`: how a device file or a FIFO travels in a zip (APPNOTE.TXT 4.3.7, 4.3.12, 4.4.15).
inline std::string zipWithUnixMode(const std::string& name, std::uint32_t mode) {
    std::string z;
    auto u16 = [&](unsigned v) {
        z += static_cast<char>(v & 0xFF);
        z += static_cast<char>((v >> 8) & 0xFF);
    };
    auto u32 = [&](std::uint32_t v) {
        u16(v & 0xFFFF);
        u16(v >> 16);
    };
    u32(0x04034b50);  // local file header: stored, empty (CRC 0), dated 1980-01-01
    for (unsigned v : {10u, 0u, 0u, 0u, 0x21u}) u16(v);
    for (int i = 0; i < 3; ++i) u32(0);
    u16(static_cast<unsigned>(name.size()));
    u16(0);
    z += name;
    const std::uint32_t central = static_cast<std::uint32_t>(z.size());
    u32(0x02014b50);  // central directory header, made by Unix (3)
    for (unsigned v : {0x0314u, 10u, 0u, 0u, 0u, 0x21u}) u16(v);
    for (int i = 0; i < 3; ++i) u32(0);
    u16(static_cast<unsigned>(name.size()));
    for (int i = 0; i < 4; ++i) u16(0);
    u32(mode << 16);
    u32(0);
    z += name;
    const std::uint32_t size = static_cast<std::uint32_t>(z.size()) - central;
    u32(0x06054b50);  // end of central directory
    for (unsigned v : {0u, 0u, 1u, 1u}) u16(v);
    u32(size);
    u32(central);
    u16(0);
    return z;
}

// The reference solution's files of a lab, as zip entries under `prefix`.
inline std::vector<ZipEntry> referenceEntries(const std::string& prefix, const std::string& extra = "") {
    std::vector<ZipEntry> out;
    for (const fs::directory_entry& e : fs::directory_iterator(kSource / "reference_solutions" / kLab))
        out.push_back({prefix + kLab + "/" + e.path().filename().string(), readFile(e.path()) + extra});
    return out;
}

inline void copyReference(const fs::path& into, const std::string& extra = "") {
    fs::create_directories(into / kLab);
    for (const fs::directory_entry& e : fs::directory_iterator(kSource / "reference_solutions" / kLab))
        writeFile(into / kLab / e.path().filename(), readFile(e.path()) + extra);
}

}  // namespace shaderlab::batch_testing
