// Writing the class page's folder: the pictures the page shows copied into pictures/<lab>/ (so the
// page stands alone), then class.json and index.html, each written whole or not at all.
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "class_markup.h"
#include "grader/base/atomic_file.h"
#include "shaderlab/classview/class_report.h"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace shaderlab::classview {

namespace {

constexpr std::uintmax_t kMaxPictureBytes = std::uintmax_t(32) << 20;

// labs/<lab>/hints/hints.json as (mistake, scene, image) -> picture file, absolute.
using HintFiles = std::map<std::string, std::string>;

std::string hintKey(const std::string& mistake, const std::string& scene, const std::string& image) {
    return mistake + "\n" + scene + "\n" + image;
}

HintFiles readHintIndex(const std::string& labs_root, const std::string& lab,
                        std::vector<std::string>* warnings) {
    HintFiles files;
    if (labs_root.empty()) return files;
    const fs::path dir = fs::path(labs_root) / lab / "hints";
    std::ifstream in(dir / "hints.json", std::ios::binary);
    if (!in) return files;  // a lab without known mistakes
    std::ostringstream s;
    s << in.rdbuf();
    const json doc = json::parse(s.str(), nullptr, false);
    if (doc.is_discarded() || !doc.is_object() || !doc.contains("hints") || !doc["hints"].is_array()) {
        warnings->push_back((dir / "hints.json").string() +
                            ": not a hints index; the lab's pictures are left out");
        return files;
    }
    for (const json& h : doc["hints"]) {
        if (!h.is_object()) continue;
        const auto text = [&](const char* key) {
            return h.contains(key) && h[key].is_string() ? h[key].get<std::string>() : std::string();
        };
        const std::string file = text("file");
        if (file.empty() || file[0] == '/' || file.find("..") != std::string::npos) continue;
        const std::string path = (dir / file).string();
        files.emplace(hintKey(text("mistake"), text("scene"), text("image")), path);
        files.emplace(hintKey(text("mistake"), "", ""), path);  // any picture of the mistake
    }
    return files;
}

bool copyFile(const std::string& from, const fs::path& to, std::string* error) {
    std::error_code ec;
    const std::uintmax_t size = fs::file_size(from, ec);
    if (ec || !fs::is_regular_file(from, ec) || size > kMaxPictureBytes) {
        *error = from + ": " + (ec ? "missing" : "not a picture file");
        return false;
    }
    std::ifstream in(from, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    if (!in) {
        *error = from + ": cannot read";
        return false;
    }
    return grader::writeFileAtomically(to.string(), s.str(), error, false);
}

// Copies one picture into pictures/<lab>/<name>; the path relative to `out` or "" with a warning.
std::string placePicture(const fs::path& out, const std::string& lab, const std::string& name,
                         const std::string& source, std::vector<std::string>* warnings) {
    if (source.empty()) return "";
    const std::string rel = "pictures/" + safeName(lab) + "/" + name;
    std::string why;
    if (!grader::createFoldersInside(out.string(), "pictures/" + safeName(lab), &why) ||
        !copyFile(source, out / rel, &why)) {
        warnings->push_back(why);
        return "";
    }
    return rel;
}

void placeLabPictures(const fs::path& out, const std::string& labs_root, LabClass* lab,
                      std::vector<std::string>* warnings) {
    if (lab->mistakes.empty()) return;
    const HintFiles hints = readHintIndex(labs_root, lab->id, warnings);
    for (MistakeTally& t : lab->mistakes) {
        const std::string base = safeName(t.mistake);
        t.expected_picture = placePicture(out, lab->id, base + ".expected.png", t.reference_source, warnings);
        auto it = hints.find(hintKey(t.mistake, t.scene, t.image));
        if (it == hints.end()) it = hints.find(hintKey(t.mistake, "", ""));
        if (it != hints.end()) {
            t.mistake_picture = placePicture(out, lab->id, base + ".mistake.png", it->second, warnings);
            t.mistake_picture_is_students = false;
        }
        if (t.mistake_picture.empty() && !t.student_source.empty()) {
            t.mistake_picture = placePicture(out, lab->id, base + ".student.png", t.student_source, warnings);
            t.mistake_picture_is_students = !t.mistake_picture.empty();
        }
    }
}

// The pictures an earlier page left (the new page may show others): only files named as this
// library names them, in pictures/<lab>/; anything else there is not ours and stays.
bool removeOldPictures(const fs::path& pictures, std::string* error) {
    std::error_code ec;
    if (!fs::is_directory(fs::symlink_status(pictures, ec))) return true;
    const auto ours = [](const std::string& name) {
        for (const char* end : {".expected.png", ".mistake.png", ".student.png"}) {
            const std::string e = end;
            if (name.size() > e.size() && name.compare(name.size() - e.size(), e.size(), e) == 0) return true;
        }
        return false;
    };
    for (const fs::directory_entry& lab : fs::directory_iterator(pictures, ec)) {
        if (!lab.is_directory(ec) || lab.is_symlink(ec)) continue;
        for (const fs::directory_entry& f : fs::directory_iterator(lab.path(), ec))
            if (f.is_regular_file(ec) && !f.is_symlink(ec) && ours(f.path().filename().string()) &&
                !fs::remove(f.path(), ec)) {
                *error = f.path().string() + ": cannot remove it (" + ec.message() + ")";
                return false;
            }
    }
    return true;
}

}  // namespace

bool writeClassPage(ClassReport report, const std::string& out_dir, const std::string& labs_root,
                    std::vector<std::string>* warnings, std::string* error) {
    std::error_code ec;
    const fs::path out = fs::absolute(out_dir, ec).lexically_normal();
    // Inside the results folder the page's files could meet a student's folder ("pictures").
    const fs::path from_results = out.lexically_relative(fs::path(report.results_dir));
    if (!report.results_dir.empty() && !from_results.empty() && *from_results.begin() != "..") {
        *error = out_dir + ": inside the results folder " + report.results_dir +
                 "; write the page beside it (e.g. --out class/)";
        return false;
    }
    fs::create_directories(out, ec);
    if (!fs::is_directory(out, ec) || fs::is_symlink(out, ec)) {
        *error = out_dir + ": cannot make this folder";
        return false;
    }
    if (!removeOldPictures(out / "pictures", error)) return false;
    for (LabClass& lab : report.labs) placeLabPictures(out, labs_root, &lab, warnings);
    for (ReteachItem& item : report.reteach)
        for (const LabClass& lab : report.labs)
            for (const MistakeTally& t : lab.mistakes)
                if (lab.id == item.lab && t.mistake == item.mistake) item.picture = t.mistake_picture;

    std::string results_href;
    const fs::path rel = fs::path(report.results_dir).lexically_relative(out);
    if (!rel.empty()) results_href = rel.generic_string() + "/";
    return grader::writeFileAtomically((out / "class.json").string(), classToJson(report), error) &&
           grader::writeFileAtomically((out / "index.html").string(), classToHtml(report, results_href),
                                       error);
}

}  // namespace shaderlab::classview
