// White-box checks of the inner loops (src/kernels.h): the filter passes against a plain
// convolution, and the portable and AVX2 builds against each other through the public metrics.
#include "../src/kernels.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "../src/filter.h"
#include "grader/metrics/metrics.h"
#include "test_images.h"

namespace grader {
namespace {

// Resets the automatic kernel choice when a test ends, however it ends.
struct KernelChoice {
    explicit KernelChoice(const detail::KernelTable* table) { detail::setKernelsForTesting(table); }
    ~KernelChoice() { detail::setKernelsForTesting(nullptr); }
};

std::vector<const detail::KernelTable*> builds() {
    std::vector<const detail::KernelTable*> tables = {&detail::portableKernels()};
    if (detail::avx2Kernels() != nullptr) tables.push_back(detail::avx2Kernels());
    return tables;
}

// An even (w[-k] = w[k]) or odd (w[-k] = -w[k]) kernel with arbitrary weights.
detail::Kernel makeKernel(int radius, bool odd) {
    detail::Kernel kernel;
    kernel.radius = radius;
    for (int k = -radius; k <= radius; ++k) {
        const double g = std::exp(-0.3 * k * k);
        const double w = odd ? -k * g : g * (1.0 + 0.1 * k * k);
        kernel.taps.push_back(static_cast<float>(w));
        kernel.taps_f64.push_back(static_cast<float>(w));
    }
    return kernel;
}

// out[x] = sum_k w[k] * row[border(x + k)].
std::vector<double> convolve(const std::vector<float>& row, const detail::Kernel& kernel,
                             detail::Border border) {
    const int n = static_cast<int>(row.size());
    std::vector<double> out(n, 0.0);
    for (int x = 0; x < n; ++x) {
        for (int k = -kernel.radius; k <= kernel.radius; ++k) {
            out[x] += kernel.taps[k + kernel.radius] *
                      static_cast<double>(row[detail::borderIndex(x + k, n, border)]);
        }
    }
    return out;
}

TEST(Kernels, BorderIndex) {
    using detail::Border;
    EXPECT_EQ(detail::borderIndex(-1, 5, Border::ClampToEdge), 0);
    EXPECT_EQ(detail::borderIndex(7, 5, Border::ClampToEdge), 4);
    // scipy 'reflect': d c b a | a b c d | d c b a
    EXPECT_EQ(detail::borderIndex(-1, 4, Border::Reflect), 0);
    EXPECT_EQ(detail::borderIndex(-2, 4, Border::Reflect), 1);
    EXPECT_EQ(detail::borderIndex(4, 4, Border::Reflect), 3);
    EXPECT_EQ(detail::borderIndex(5, 4, Border::Reflect), 2);
    EXPECT_EQ(detail::borderIndex(-5, 2, Border::Reflect), 0);  // repeats for tiny n: a b | b a | a b
}

TEST(Kernels, HorizontalPassesMatchAPlainConvolution) {
    for (const detail::KernelTable* table : builds()) {
        KernelChoice choice(table);
        for (int width : {1, 3, 8, 13, 37, 64}) {
            std::vector<float> row(width);
            test::Lcg random(width);
            for (float& v : row) v = random.next();
            for (detail::Border border : {detail::Border::ClampToEdge, detail::Border::Reflect}) {
                const int radius = 4;
                if (border == detail::Border::Reflect && width < 2) continue;
                const detail::Kernel even = makeKernel(radius, false);
                const detail::Kernel odd = makeKernel(radius, true);
                std::vector<float> padded(detail::paddedRowLength(width + 2 * radius), 0.0f);
                std::copy(row.begin(), row.end(), padded.begin() + radius);
                detail::fillBorders(padded.data(), width, radius, border);
                const detail::ColumnOffsets columns(radius);
                const auto taps =
                    detail::horizontalTaps(static_cast<const float*>(padded.data()), radius, radius, columns);
                std::vector<float> a(width + 8), b(width + 8), c(width + 8);
                detail::filterEvenOddEven(taps, 0, width, even, odd, even, a.data(), b.data(), c.data());
                const std::vector<double> expected_even = convolve(row, even, border);
                const std::vector<double> expected_odd = convolve(row, odd, border);
                for (int x = 0; x < width; ++x) {
                    ASSERT_NEAR(a[x], expected_even[x], 1e-5)
                        << table->name << " width " << width << " x " << x;
                    ASSERT_NEAR(b[x], expected_odd[x], 1e-5)
                        << table->name << " width " << width << " x " << x;
                    ASSERT_NEAR(c[x], expected_even[x], 1e-5);
                }
                detail::filterEven(taps, 0, width, even, a.data());
                for (int x = 0; x < width; ++x) ASSERT_NEAR(a[x], expected_even[x], 1e-5);
            }
        }
    }
}

TEST(Kernels, TwoRowVerticalPassMatchesTwoSingleRowPasses) {
    // A column of 9 rows of 21 values; output rows y and y + 1 from one ring window.
    const int width = 21, height = 9, radius = 3;
    for (const detail::KernelTable* table : builds()) {
        KernelChoice choice(table);
        const detail::RowRing ring(height, radius, detail::Border::ClampToEdge);
        const std::size_t stride = detail::ringStride(width);
        std::vector<float> slots(stride * ring.slots(), 0.0f);
        test::Lcg random(3);
        std::vector<std::vector<float>> image(height, std::vector<float>(width));
        for (auto& row : image) {
            for (float& v : row) v = random.next();
        }
        const detail::Kernel even = makeKernel(radius, false);
        const detail::Kernel odd = makeKernel(radius, true);
        std::vector<int> window(2 * radius + 2);
        for (int y = 0; y + 1 < height; y += 2) {
            for (int row = 0; row <= ring.lastRowNeeded(y); ++row) {
                std::copy(image[row].begin(), image[row].end(),
                          slots.begin() + (row % ring.slots()) * stride);
            }
            ring.window(y, window.data());
            const auto taps =
                ring.taps(static_cast<const float*>(slots.data()), stride, window.data(), radius);
            std::vector<float> o0(32), e0(32), o1(32), e1(32), single(32);
            detail::filterOddEvenRows2(taps, 0, width, odd, even, o0.data(), e0.data(), o1.data(), e1.data());
            for (int x = 0; x < width; ++x) {
                double expected[2][2] = {{0, 0}, {0, 0}};  // [row][odd, even]
                for (int r = 0; r < 2; ++r) {
                    for (int k = -radius; k <= radius; ++k) {
                        const double v =
                            image[detail::borderIndex(y + r + k, height, detail::Border::ClampToEdge)][x];
                        expected[r][0] += odd.taps[k + radius] * v;
                        expected[r][1] += even.taps[k + radius] * v;
                    }
                }
                ASSERT_NEAR(o0[x], expected[0][0], 1e-5) << table->name << " y " << y << " x " << x;
                ASSERT_NEAR(e0[x], expected[0][1], 1e-5);
                ASSERT_NEAR(o1[x], expected[1][0], 1e-5);
                ASSERT_NEAR(e1[x], expected[1][1], 1e-5);
            }
            detail::filterEven(taps, 0, width, even, single.data());
            for (int x = 0; x < width; ++x) ASSERT_NEAR(single[x], e0[x], 1e-6);
        }
    }
}

TEST(Kernels, ColourRowDecodesSrgbLikeTheFormula) {
    // For grey input the luminance output is the linear value itself (the sRGB -> XYZ matrix's Y
    // row sums to 1 and Y_white is 1), so it shows the sRGB decode (IEC 61966-2-1) alone: every
    // 8-bit value, a fine sweep of [0, 1] and the values the clamp handles, against the formula
    // in double. Measured: 4.9e-7 (portable), 4.0e-7 (AVX2), against 3e-8 for the 4097-entry
    // table this replaced; either is far below what FLIP resolves.
    std::vector<float> values;
    for (int i = 0; i <= 255; ++i) values.push_back(i / 255.0f);
    for (int i = 0; i <= 100000; ++i) values.push_back(i / 100000.0f);
    for (float v : {-1.0f, 2.0f, 0.04045f, std::nextafter(0.04045f, 1.0f), NAN}) values.push_back(v);
    const int width = static_cast<int>(values.size());
    const std::size_t padded = static_cast<std::size_t>(detail::paddedRowLength(width));
    std::vector<float> grey(padded, 0.0f);
    std::copy(values.begin(), values.end(), grey.begin());
    const float* rows[3] = {grey.data(), grey.data(), grey.data()};
    for (const detail::KernelTable* table : builds()) {
        std::vector<float> cx(padded), cz(padded), luminance(padded);
        table->flip_colour_row(rows, width, cx.data(), cz.data(), luminance.data());
        double worst = 0.0;
        for (int i = 0; i < width; ++i) {
            const double v = std::isnan(values[i]) ? 0.0 : std::min(1.0, std::max(0.0, double(values[i])));
            const double exact = v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
            const double error = std::abs(luminance[i] - exact) / std::max(exact, 1e-3);
            worst = std::max(worst, error);
            ASSERT_LT(error, 1e-6) << table->name << ": value " << values[i] << " gives " << luminance[i]
                                   << ", the formula " << exact;
        }
        char worst_text[32];
        std::snprintf(worst_text, sizeof worst_text, "%.3g", worst);
        RecordProperty(std::string(table->name) + "_worst_relative_error", worst_text);
    }
}

TEST(Kernels, BuildsAgreeThroughTheMetrics) {
    const std::vector<const detail::KernelTable*> tables = builds();
    if (tables.size() < 2) GTEST_SKIP() << "this CPU runs only the portable build";
    const Image a = test::patternImage(77, 53);
    const Image b = test::withNoise(test::patternImage(77, 53, 0.3), 0.1f, 8);
    double psnr[2], ssim[2], flip[2], median[2];
    for (int i = 0; i < 2; ++i) {
        KernelChoice choice(tables[i]);
        psnr[i] = computePsnr(a, b).psnr_db;
        ssim[i] = computeSsim(a, b).ssim;
        const FlipResult result = computeFlip(a, b);
        flip[i] = result.mean;
        median[i] = result.weighted_median;
    }
    EXPECT_NEAR(psnr[0], psnr[1], 1e-9);
    EXPECT_NEAR(ssim[0], ssim[1], 1e-8);
    EXPECT_NEAR(flip[0], flip[1], 1e-6);
    EXPECT_NEAR(median[0], median[1], 1e-5);
}

}  // namespace
}  // namespace grader
