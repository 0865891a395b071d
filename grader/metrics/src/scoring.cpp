// Verdicts and points; see scoring.h.
#include "grader/metrics/scoring.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include "image_access.h"

namespace grader {

namespace {

std::string fmt(const char* format, double a, double b) {
    char buf[160];
    std::snprintf(buf, sizeof buf, format, a, b);
    return buf;
}

// "<what> <value><unit> is <relation> <limit><unit>", with as many decimals (from `digits`, at
// most 6) as it takes for the two numbers to read differently: never "0.950 is below 0.950".
std::string compared(const char* what, double value, const char* relation, double limit, int digits,
                     const char* unit = "") {
    const auto [a, b] = formatDistinct(value, limit, digits);
    return std::string(what) + " " + a + unit + " is " + relation + " " + b + unit;
}

MetricSet measure(const Image& ref, const Image& test, const Mask* mask, float tolerance,
                  ToleranceCompareResult* compare_out, FlipResult* flip_out) {
    MetricSet m;
    PsnrConfig pc;
    pc.mask = mask;
    const PsnrResult psnr = computePsnr(ref, test, pc);
    m.psnr_db = psnr.psnr_db;
    m.pixel_count = psnr.pixel_count;
    SsimConfig sc;
    sc.mask = mask;
    SsimResult ssim = computeSsim(ref, test, sc);
    // SSIM leaves a 5-pixel border out of its mean; a mask lying entirely inside that border
    // would have no SSIM at all, so such an image is judged on the whole frame's SSIM instead.
    if (!ssim.ok && mask) ssim = computeSsim(ref, test, SsimConfig{});
    // An image smaller than the window has no SSIM at all: the other metrics decide.
    m.ssim_defined = ssim.ok;
    m.ssim = ssim.ok ? ssim.ssim : 0.0;
    FlipConfig fc;
    fc.mask = mask;
    fc.want_map = flip_out != nullptr;
    FlipResult flip = computeFlip(ref, test, fc);
    m.flip_mean = flip.mean;
    m.flip_weighted_median = flip.weighted_median;
    ToleranceCompareConfig cc;
    cc.mask = mask;
    cc.tolerance = tolerance;
    ToleranceCompareResult cmp = compareShiftTolerant(ref, test, cc);
    m.mismatch_fraction = cmp.mismatch_fraction;
    if (compare_out) *compare_out = std::move(cmp);
    if (flip_out) *flip_out = std::move(flip);
    return m;
}

}  // namespace

std::pair<std::string, std::string> formatDistinct(double value, double limit, int digits) {
    char a[64], b[64];
    for (;; ++digits) {
        std::snprintf(a, sizeof a, "%.*f", digits, value);
        std::snprintf(b, sizeof b, "%.*f", digits, limit);
        if (std::string(a) != b || digits >= 6) break;
    }
    return {a, b};
}

Image quantise8(const Image& image) {
    Image out = image;
    for (float& v : out.pixels) v = static_cast<float>(detail::level8(v)) / 255.0f;
    return out;
}

Image rgbeRoundTrip(const Image& image) {
    Image out = image;
    if (image.channels < 3) return out;
    for (std::size_t p = 0; p + 2 < out.pixels.size(); p += static_cast<std::size_t>(out.channels)) {
        float c[3];
        for (int k = 0; k < 3; ++k) {
            const float v = out.pixels[p + static_cast<std::size_t>(k)];
            c[k] = std::isfinite(v) && v > 0.0f ? v : 0.0f;
        }
        const float largest = std::fmax(c[0], std::fmax(c[1], c[2]));
        if (largest < 1e-32f) {
            for (int k = 0; k < 3; ++k) out.pixels[p + static_cast<std::size_t>(k)] = 0.0f;
            continue;
        }
        // Encode as stb_image_write does, decode as stb_image does.
        int exponent = 0;
        const float normalize = std::frexp(largest, &exponent) * 256.0f / largest;
        const float unit = std::ldexp(1.0f, exponent - 8);
        for (int k = 0; k < 3; ++k) {
            const float mantissa = std::floor(std::fmin(c[k] * normalize, 255.0f));
            out.pixels[p + static_cast<std::size_t>(k)] = mantissa * unit;
        }
    }
    return out;
}

namespace {

// Hdr range: RGBE rounding, then both images over the reference's peak when it exceeds 1.
void toUnitRange(const Image& reference, const Image& test, Image* ref_out, Image* test_out, double* scale) {
    *ref_out = rgbeRoundTrip(reference);
    *test_out = rgbeRoundTrip(test);
    float peak = 1.0f;
    for (std::size_t p = 0; p < ref_out->pixels.size(); ++p)
        if (ref_out->channels < 4 || p % 4 != 3) peak = std::fmax(peak, ref_out->pixels[p]);
    *scale = peak;
    for (Image* img : {ref_out, test_out})
        for (float& v : img->pixels) v = std::fmin(v / peak, 1.0f);
}

}  // namespace

ImageVerdict judgeImage(const Image& reference, const std::vector<std::uint8_t>& reference_coverage,
                        const Image& test, const std::vector<std::uint8_t>& test_coverage,
                        const Thresholds& thresholds, ImageRange range) {
    ImageVerdict v;
    if (reference.width != test.width || reference.height != test.height) {
        v.reasons.push_back(
            fmt("image is %.0f pixels wide, the reference %.0f", test.width, reference.width));
        return v;
    }
    const NonFiniteResult nf = scanNonFinite(test);
    v.nan_count = nf.nan_pixels;
    v.inf_count = nf.inf_pixels;
    v.non_finite_box = nf.bounding_box;
    v.non_finite_first = nf.first_positions;

    // Covered: drawn by the reference or by the student, so a missing object and an extra one
    // both count. When nothing is covered (a fullscreen pass, or an empty frame) the whole
    // frame is graded.
    const std::size_t n = static_cast<std::size_t>(test.width) * test.height;
    Mask covered(test.width, test.height, 0);
    for (std::size_t i = 0; i < n; ++i) {
        const bool r = reference_coverage.size() != n || reference_coverage[i];
        const bool t = test_coverage.size() != n || test_coverage[i];
        covered.values[i] = (r || t) ? 1 : 0;
    }
    v.covered_pixels = covered.count();
    if (v.covered_pixels == 0) covered = Mask(test.width, test.height, 1);

    if (range == ImageRange::Display && detail::quantisedPixelsEqual(reference, test)) {
        // Both quantise to one image: what each metric gives when it finds its inputs identical
        // (PSNR infinite, SSIM 1 where the image holds SSIM's window, FLIP 0 with an all-zero
        // map, no mismatch), without either copy. MetricStress.QuantisedEqualImagesGetWhatThe-
        // MetricsGive compares this with the metrics themselves, field by field.
        const int side = 2 * ssimWindowRadius(SsimConfig{}.sigma) + 1;
        MetricSet same;
        same.psnr_db = std::numeric_limits<double>::infinity();
        same.ssim_defined = test.width >= side && test.height >= side;
        same.ssim = same.ssim_defined ? 1.0 : 0.0;
        same.pixel_count = covered.count();
        v.covered = same;
        v.frame = same;
        v.frame.pixel_count = n;
        v.mismatches = Mask(test.width, test.height, 0);
        v.flip_map.assign(n, 0.0f);
    } else {
        Image ref8, test8;
        if (range == ImageRange::Hdr) {
            toUnitRange(reference, test, &ref8, &test8, &v.hdr_scale);
        } else {
            ref8 = quantise8(reference);
            test8 = quantise8(test);
        }
        ToleranceCompareResult cmp;
        FlipResult flip;
        v.covered = measure(ref8, test8, &covered, thresholds.pixel_tolerance, &cmp, &flip);
        // When every pixel is graded anyway the whole-frame numbers are the same: skip the work.
        v.frame = covered.count() == n
                      ? v.covered
                      : measure(ref8, test8, nullptr, thresholds.pixel_tolerance, nullptr, nullptr);
        v.worst = cmp.worst;
        v.mismatches = std::move(cmp.mismatches);
        v.flip_map = std::move(flip.error_map);
    }
    v.graded = covered;

    v.checks_met = 0;
    if (v.covered.psnr_db >= thresholds.psnr_min_db)
        ++v.checks_met;
    else
        v.reasons.push_back(compared("PSNR", v.covered.psnr_db, "below", thresholds.psnr_min_db, 1, " dB"));
    if (!v.covered.ssim_defined)
        v.checks_total = 3;
    else if (v.covered.ssim >= thresholds.ssim_min)
        ++v.checks_met;
    else
        v.reasons.push_back(compared("SSIM", v.covered.ssim, "below", thresholds.ssim_min, 3));
    if (v.covered.flip_mean <= thresholds.flip_mean_max)
        ++v.checks_met;
    else
        v.reasons.push_back(compared("FLIP mean", v.covered.flip_mean, "above", thresholds.flip_mean_max, 3));
    if (v.covered.mismatch_fraction <= thresholds.mismatch_max) {
        ++v.checks_met;
    } else {
        std::string where;
        if (!v.worst.tile.empty()) {
            char buf[96];
            std::snprintf(buf, sizeof buf, " (worst around x=%d, y=%d)", v.worst.centre.x, v.worst.centre.y);
            where = buf;
        }
        const auto [got, allowed] =
            formatDistinct(100.0 * v.covered.mismatch_fraction, 100.0 * thresholds.mismatch_max, 1);
        v.reasons.push_back(got + " % of covered pixels differ, more than " + allowed + " %" + where);
    }
    if (nf.any()) {
        char buf[200];
        std::snprintf(buf, sizeof buf,
                      "%zu pixels are NaN and %zu are Inf, first at x=%d, y=%d (e.g. pow() of a negative "
                      "base, normalize() of a zero vector, division by zero)",
                      nf.nan_pixels, nf.inf_pixels, nf.first_positions.empty() ? 0 : nf.first_positions[0].x,
                      nf.first_positions.empty() ? 0 : nf.first_positions[0].y);
        v.reasons.insert(v.reasons.begin(), buf);
    }
    v.passed = !nf.any() && v.checks_met == v.checks_total;
    return v;
}

}  // namespace grader
