// Known-mistake hints: storage and matching; see mistake_hints.h.
#include "shaderlab/grading/mistake_hints.h"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "grader/metrics/metrics.h"
#include "grader/metrics/scoring.h"
#include "grader/reports/report_images.h"
#include "shaderlab/base/paths.h"

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

namespace shaderlab {

grader::Image hintPicture(const grader::Image& picture, int factor) {
    const grader::Image small = grader::quantise8(grader::downsample(picture, factor));
    grader::Image rgb(small.width, small.height, 3);
    for (int y = 0; y < small.height; ++y)
        for (int x = 0; x < small.width; ++x)
            for (int c = 0; c < 3; ++c) rgb.at(x, y, c) = small.at(x, y, small.channels >= 3 ? c : 0);
    return rgb;
}

bool loadLabHints(const std::string& hints_dir, LabHints* out, std::string* error) {
    *out = LabHints{};
    const fs::path index = fs::path(hints_dir) / "hints.json";
    std::error_code ec;
    if (!fs::exists(index, ec)) return true;
    const FileText t = readFile(index.string(), 4u << 20);
    const json doc = t.ok ? json::parse(t.text, nullptr, false) : json();
    if (!t.ok || !doc.is_object() || !doc.value("hints", json()).is_array()) {
        *error = index.string() + ": not a hints index (run `shaderlab goldens`)";
        return false;
    }
    out->factor = doc.value("factor", 2);
    out->min_psnr_db = doc.value("min_psnr_db", 40.0);
    out->unstable = doc.value("unstable", std::vector<std::string>{});
    out->renderer = doc.value("renderer", "");
    for (const json& h : doc["hints"]) {
        MistakeHint m;
        m.mistake = h.value("mistake", "");
        m.about = h.value("about", "");
        m.scene = h.value("scene", "");
        m.image = h.value("image", "");
        m.file = h.value("file", "");
        // Only plain relative names: the index cannot send the reader elsewhere.
        if (m.file.empty() || m.file.find("..") != std::string::npos || m.file[0] == '/') {
            *error = index.string() + ": bad file name \"" + m.file + "\"";
            return false;
        }
        if (!grader::readPng((fs::path(hints_dir) / m.file).string(), &m.picture, error)) return false;
        out->hints.push_back(std::move(m));
    }
    return true;
}

bool writeLabHints(const std::string& hints_dir, const LabHints& hints, std::string* error) {
    std::error_code ec;
    fs::remove_all(hints_dir, ec);
    if (hints.hints.empty() && hints.unstable.empty()) return true;
    fs::create_directories(hints_dir, ec);
    json list = json::array();
    for (const MistakeHint& m : hints.hints) {
        const fs::path file = fs::path(hints_dir) / m.file;
        fs::create_directories(file.parent_path(), ec);
        if (!grader::writePng(m.picture, file.string(), error)) return false;
        list.push_back({{"mistake", m.mistake},
                        {"about", m.about},
                        {"scene", m.scene},
                        {"image", m.image},
                        {"file", m.file}});
    }
    const json doc = {{"$comment", "Written by `shaderlab goldens` from tests/corpus; do not edit."},
                      {"factor", hints.factor},
                      {"min_psnr_db", hints.min_psnr_db},
                      {"hints", list},
                      {"unstable", hints.unstable},
                      {"renderer", hints.renderer}};
    std::ofstream out(fs::path(hints_dir) / "hints.json", std::ios::binary);
    out << doc.dump(1) << "\n";
    if (!out) {
        *error = hints_dir + "/hints.json: cannot write";
        return false;
    }
    return true;
}

void dropAmbiguousHints(LabHints* hints) {
    std::vector<bool> ambiguous(hints->hints.size(), false);
    for (std::size_t i = 0; i < hints->hints.size(); ++i) {
        for (std::size_t j = i + 1; j < hints->hints.size(); ++j) {
            const MistakeHint& a = hints->hints[i];
            const MistakeHint& b = hints->hints[j];
            if (a.scene != b.scene || a.image != b.image || a.picture.width != b.picture.width ||
                a.picture.height != b.picture.height)
                continue;
            const grader::PsnrResult p = grader::computePsnr(a.picture, b.picture);
            if (p.ok && p.psnr_db >= hints->min_psnr_db) ambiguous[i] = ambiguous[j] = true;
        }
    }
    std::vector<MistakeHint> kept;
    for (std::size_t i = 0; i < hints->hints.size(); ++i)
        if (!ambiguous[i]) kept.push_back(std::move(hints->hints[i]));
    hints->hints = std::move(kept);
}

std::map<std::string, grader::ReportHint> explainFailures(
    const LabHints& hints, const std::map<std::string, FailingPicture>& failing) {
    // Mistake -> (scene -> PSNR), or absent once one of its pictures does not match.
    std::map<std::string, std::map<std::string, double>> matched;
    std::map<std::string, bool> explains;
    std::map<std::string, const MistakeHint*> first;
    for (const MistakeHint& m : hints.hints) {
        auto [it, fresh] = explains.emplace(m.mistake, true);
        if (fresh) first[m.mistake] = &m;
        if (!it->second) continue;
        const auto f = failing.find(m.scene);
        if (f == failing.end() || f->second.image != m.image) {
            it->second = false;
            continue;
        }
        // The student's picture as its PNG holds it, like the stored mistakes'.
        const grader::HintComparison c = grader::compareWithHint(
            grader::quantise8(f->second.picture), grader::quantise8(f->second.reference), m.picture,
            f->second.graded, hints.factor, hints.min_psnr_db);
        if (!c.matches) {
            it->second = false;
            continue;
        }
        matched[m.mistake][m.scene] = c.psnr_to_hint_db;
    }
    std::map<std::string, grader::ReportHint> out;
    for (const auto& [mistake, scenes] : matched) {
        if (!explains[mistake]) continue;
        for (const auto& [scene, psnr] : scenes) {
            grader::ReportHint& h = out[scene];
            if (!h.mistake.empty() && h.psnr_db >= psnr) continue;
            h.mistake = mistake;
            h.about = first[mistake]->about;
            h.image = failing.at(scene).image;
            h.psnr_db = psnr;
        }
    }
    return out;
}

}  // namespace shaderlab
