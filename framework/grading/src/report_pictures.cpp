// The pictures the report shows of one judged image, written into the report folder. It does
// not judge anything: the verdict comes in made (grading.cpp), and so do the images.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>

#include "grader/base/atomic_file.h"
#include "grader/metrics/heatmap.h"
#include "grader/metrics/scoring.h"
#include "grader/reports/report_images.h"
#include "grading_detail.h"

namespace fs = std::filesystem;

namespace shaderlab::grading_detail {

namespace {

// Writes one PNG and returns its path relative to the report folder (empty on failure, with
// the reason added to `errors`).
std::string writeImage(const grader::Image& img, const fs::path& out_dir, const fs::path& rel,
                       std::vector<std::string>* errors) {
    if (out_dir.empty()) return {};  // a grade without pictures (GradeOptions::out_dir)
    std::string err;
    // Folder by folder, refusing a link planted on the way (atomic_file.h); writePng refuses one
    // at the file's own name.
    if (!grader::createFoldersInside(out_dir.string(), rel.parent_path().string(), &err) ||
        !grader::writePng(img, (out_dir / rel).string(), &err)) {
        errors->push_back(err);
        return {};
    }
    return rel.generic_string();
}

// The reference picture when the reference is a stored golden PNG: the file itself, copied (its
// pixels are exactly the image compared), instead of encoding the same pixels again. Falls back
// to writing `img` when the copy fails.
std::string copyOrWriteImage(const std::string& golden, const grader::Image& img, const fs::path& out_dir,
                             const fs::path& rel, std::vector<std::string>* errors) {
    if (out_dir.empty()) return {};
    if (!golden.empty()) {
        // The same care as writeImage: no folder or file of the output written through a link.
        std::ifstream in(golden, std::ios::binary);
        std::ostringstream bytes;
        bytes << in.rdbuf();
        std::string err;
        if (in && grader::createFoldersInside(out_dir.string(), rel.parent_path().string(), &err) &&
            grader::writeFileAtomically((out_dir / rel).string(), bytes.str(), &err, false))
            return rel.generic_string();
        if (!err.empty()) {
            errors->push_back(err);
            return {};
        }
    }
    return writeImage(img, out_dir, rel, errors);
}

// Whether two images make the same PNG: the same size and channels, and every value at the same
// of the 256 levels writePng stores.
bool samePicture(const grader::Image& a, const grader::Image& b) {
    if (a.width != b.width || a.height != b.height || a.channels != b.channels) return false;
    return grader::quantise8(a).pixels == grader::quantise8(b).pixels;
}

}  // namespace

ShownPictures writeReportPictures(const PicturePlace& place, const GradedImage& g,
                                  const grader::ImageVerdict& v, const grader::Image& mine,
                                  const grader::Image& theirs, grader::ReportPass* rp,
                                  std::vector<std::string>* errors) {
    const fs::path& out_dir = place.out_dir;
    const fs::path base = fs::path(place.lab) / place.scene;
    const std::string suffix = place.final_image ? "" : "." + g.id;
    const fs::path student_rel = base / ("student" + suffix + ".png");
    const fs::path reference_rel = base / ("reference" + suffix + ".png");
    const bool golden_png = place.reference_source != "reference_solutions" && !g.hdr;
    const std::string golden = golden_png
                                   ? goldenPath(place.stored_dir, place.scene, g.id, place.final_image, false)
                                   : std::string();
    // A passing image is never the one a known mistake explains, and the report shows it as the
    // student's picture alone (report_markup.cpp): its difference pictures would be drawn and
    // encoded for nobody. One identical to a stored reference (in the display range, where the
    // picture is the image) is that file, copied, not encoded again.
    if (v.passed) {
        if (out_dir.empty()) return {};
        if (!golden.empty() && std::isinf(v.frame.psnr_db) && v.nan_count + v.inf_count == 0) {
            rp->student_image = copyOrWriteImage(golden, mine, out_dir, student_rel, errors);
            rp->reference_image = copyOrWriteImage(golden, theirs, out_dir, reference_rel, errors);
            return {};
        }
    }
    // The pictures show what was compared: HDR images over the same scale.
    grader::Image shown_mine = mine, shown_theirs = theirs;
    if (g.hdr && v.hdr_scale > 1.0) {
        for (grader::Image* img : {&shown_mine, &shown_theirs})
            for (std::size_t k = 0; k < img->pixels.size(); ++k)
                if (img->channels < 4 || k % 4 != 3)  // colour only: alpha stays as drawn
                    img->pixels[k] = static_cast<float>(img->pixels[k] / v.hdr_scale);
    }
    // NaN and Inf show in magenta (a PNG would hold them as black or white).
    grader::Image picture = grader::markNonFinite(shown_mine);
    // A grade without pictures (the workbench's verdict) needs only what was shown, for the hints.
    if (out_dir.empty()) return {std::move(picture), std::move(shown_theirs)};
    rp->student_image = writeImage(picture, out_dir, student_rel, errors);
    // No stored PNG to copy (an HDR image, or a reference rendered now), but a passing picture
    // that is the reference's, level for level: the student's file, copied, not encoded again.
    const bool same_picture =
        golden.empty() && v.passed && !rp->student_image.empty() && samePicture(picture, shown_theirs);
    rp->reference_image = copyOrWriteImage(same_picture ? (out_dir / student_rel).string() : golden,
                                           shown_theirs, out_dir, reference_rel, errors);
    if (v.passed) return {};
    grader::HeatmapConfig hc;
    hc.outline = v.mismatches.empty() ? nullptr : &v.mismatches;
    const grader::Image heat = grader::diffHeatmap(v.flip_map, mine.width, mine.height, hc);
    if (!heat.empty()) rp->diff_image = writeImage(heat, out_dir, base / ("diff" + suffix + ".png"), errors);
    const grader::Image signed_picture = grader::signedDifference(shown_theirs, shown_mine);
    if (!signed_picture.empty())
        rp->signed_image = writeImage(signed_picture, out_dir, base / ("signed" + suffix + ".png"), errors);
    // A failing image gets a close-up: 32x32 pixels around the worst region of the
    // comparison (its 16x16 window and some context), or around the first NaN or Inf pixel
    // when nothing else differs.
    if (!v.passed) {
        grader::PixelBox region;
        if (!v.worst.tile.empty())
            region = grader::windowAround(v.worst.centre.x, v.worst.centre.y, 32, mine.width, mine.height);
        else if (!v.non_finite_first.empty())
            region = grader::windowAround(v.non_finite_first[0].x, v.non_finite_first[0].y, 32, mine.width,
                                          mine.height);
        if (!region.empty()) {
            const int factor = std::max(1, 128 / std::max(region.width(), region.height()));
            const grader::Image strip = grader::sideBySide({grader::cropZoom(picture, region, factor),
                                                            grader::cropZoom(shown_theirs, region, factor),
                                                            grader::cropZoom(heat, region, factor)});
            rp->zoom_region = region;
            if (!strip.empty())
                rp->zoom_image = writeImage(strip, out_dir, base / ("zoom" + suffix + ".png"), errors);
        }
    }
    return {std::move(picture), std::move(shown_theirs)};
}

}  // namespace shaderlab::grading_detail
