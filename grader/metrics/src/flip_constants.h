// Internal: the colour-space constants FLIP uses, shared by the pipeline (flip.cpp) and its
// inner loops (kernels_impl.h). Plain constants only (internal linkage), no functions.
#pragma once

namespace grader::detail::flip_constants {

// D65 white point of the sRGB -> XYZ matrix below, its inverse, and the matrices (sRGB
// primaries, IEC 61966-2-1, with the digits the FLIP reference implementation uses).
constexpr float kWhite[3] = {0.950428545f, 1.0f, 1.088900371f};
constexpr float kInvWhite[3] = {1.052156925f, 1.0f, 0.918357670f};
constexpr float kRgbToXyz[3][3] = {
    {10135552.0f / 24577794.0f, 8788810.0f / 24577794.0f, 4435075.0f / 24577794.0f},
    {2613072.0f / 12288897.0f, 8788810.0f / 12288897.0f, 887015.0f / 12288897.0f},
    {1425312.0f / 73733382.0f, 8788810.0f / 73733382.0f, 70074185.0f / 73733382.0f},
};
constexpr float kXyzToRgb[3][3] = {
    {3.241003275f, -1.537398934f, -0.498615861f},
    {-0.969224334f, 1.875930071f, 0.041554224f},
    {0.055639423f, -0.204011202f, 1.057148933f},
};

// CIELab's f(t): cube root above (6/29)^3, the line t / (3 delta^2) + 4/29 below.
constexpr float kLabDelta = 6.0f / 29.0f;
constexpr float kLabDeltaCube = kLabDelta * kLabDelta * kLabDelta;
constexpr float kLabLinearSlope = 1.0f / (3.0f * kLabDelta * kLabDelta);
constexpr float kLabLinearOffset = 4.0f / 29.0f;

// Where the sRGB curve's linear segment ends (IEC 61966-2-1).
constexpr float kSrgbLinearLimit = 0.04045f;  // below: linear segment v / 12.92

}  // namespace grader::detail::flip_constants
