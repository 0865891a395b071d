"""LDR-FLIP in double precision with numpy/scipy, written independently of grader/metrics/src/flip.cpp
to cross-check it: whole 2D contrast-sensitivity kernels (no separation, no trimmed taps), exact
powers and cube roots, scipy's 'nearest' borders (= clamp to edge). It follows the FLIP paper
(Andersson et al., HPG 2020) and the conventions of the authors' implementation
(github.com/NVlabs/flip); it is not that implementation.

Run: python3 grader/metrics/tests/reference/flip_reference.py   (Debian: python3-scipy)
prints the mean and weighted quartiles of the test pair (test_pair.py) that flip_test.cpp
expects.
"""
import numpy as np
from scipy import ndimage

PPD = 0.7 * (3840 / 0.7) * np.pi / 180
RGB_TO_XYZ = np.array([[10135552 / 24577794, 8788810 / 24577794, 4435075 / 24577794],
                       [2613072 / 12288897, 8788810 / 12288897, 887015 / 12288897],
                       [1425312 / 73733382, 8788810 / 73733382, 70074185 / 73733382]])
XYZ_TO_RGB = np.array([[3.241003275, -1.537398934, -0.498615861],
                       [-0.969224334, 1.875930071, 0.041554224],
                       [0.055639423, -0.204011202, 1.057148933]])
WHITE = np.array([0.950428545, 1.0, 1.088900371])


def srgb_to_linear(c):
    c = np.clip(np.nan_to_num(c, nan=0.0), 0, 1)
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def hunt_lab(rgb):
    t = rgb @ RGB_TO_XYZ.T / WHITE
    d = 6 / 29
    f = np.where(t > d ** 3, np.cbrt(np.maximum(t, 0)), t / (3 * d * d) + 4 / 29)
    lightness = 116 * f[..., 1] - 16
    return lightness, 0.01 * lightness * 500 * (f[..., 0] - f[..., 1]), 0.01 * lightness * 200 * (f[..., 1] - f[..., 2])


def hyab(p, q):
    return np.abs(p[0] - q[0]) + np.sqrt((p[1] - q[1]) ** 2 + (p[2] - q[2]) ** 2)


def flip(reference, test, ppd=PPD):
    radius = int(np.ceil(3 * np.sqrt(0.04 / (2 * np.pi ** 2)) * ppd))
    grid = np.arange(-radius, radius + 1) / ppd
    r2 = grid[None, :] ** 2 + grid[:, None] ** 2
    gauss = lambda a, b: a * np.sqrt(np.pi / b) * np.exp(-np.pi ** 2 * r2 / b)
    csf = [gauss(1, 0.0047), gauss(1, 0.0053), gauss(34.1, 0.04) + gauss(13.5, 0.025)]
    csf = [k / k.sum() for k in csf]

    sd = 0.5 * 0.082 * ppd
    fr = int(np.ceil(3 * sd))
    x = np.arange(-fr, fr + 1, dtype=float)
    g = np.exp(-x ** 2 / (2 * sd * sd))
    dg = -x * g
    ddg = (x ** 2 / sd ** 2 - 1) * g
    g /= g.sum()
    dg /= dg[dg > 0].sum()
    ddg = np.where(ddg > 0, ddg / ddg[ddg > 0].sum(), ddg / -ddg[ddg < 0].sum())

    labs, features = [], []
    for image in (reference, test):
        n = srgb_to_linear(image[..., :3].astype(np.float64)) @ RGB_TO_XYZ.T / WHITE
        ycxcz = [116 * n[..., 1] - 16, 500 * (n[..., 0] - n[..., 1]), 200 * (n[..., 1] - n[..., 2])]
        filtered = [ndimage.correlate(ycxcz[i], csf[i], mode='nearest') for i in range(3)]
        y = (filtered[0] + 16) / 116
        xyz = np.stack([(y + filtered[1] / 500) * WHITE[0], y, (y - filtered[2] / 200) * WHITE[2]], -1)
        labs.append(hunt_lab(np.clip(xyz @ XYZ_TO_RGB.T, 0, 1)))
        lum = n[..., 1]
        c1 = lambda img, k, axis: ndimage.correlate1d(img, k, axis=axis, mode='nearest')
        dx, dy = c1(c1(lum, dg, 1), g, 0), c1(c1(lum, g, 1), dg, 0)
        ddx, ddy = c1(c1(lum, ddg, 1), g, 0), c1(c1(lum, g, 1), ddg, 0)
        features.append((np.hypot(dx, dy), np.hypot(ddx, ddy)))

    cmax = hyab(hunt_lab(np.array([0.0, 1, 0])), hunt_lab(np.array([0.0, 0, 1]))) ** 0.7
    pccmax = 0.4 * cmax
    distance = hyab(labs[0], labs[1]) ** 0.7
    colour = np.where(distance < pccmax, distance * 0.95 / pccmax, 0.95 + (distance - pccmax) / (cmax - pccmax) * 0.05)
    gap = np.maximum(np.abs(features[0][0] - features[1][0]), np.abs(features[0][1] - features[1][1]))
    return colour ** (1 - np.sqrt(gap / np.sqrt(2)))


def weighted_percentile(errors, fraction):
    """The FLIP tool's definition: first sorted error whose running sum exceeds fraction * sum."""
    e = np.sort(errors.ravel())
    running = np.cumsum(e, dtype=np.float64)
    return 0.0 if running[-1] <= 0 else float(e[np.argmax(running > fraction * running[-1])])


if __name__ == '__main__':
    from test_pair import test_pair
    error = flip(*test_pair())
    print(f"mean {error.mean():.8f} p25 {weighted_percentile(error, 0.25):.8f} "
          f"p50 {weighted_percentile(error, 0.5):.8f} p75 {weighted_percentile(error, 0.75):.8f}")
