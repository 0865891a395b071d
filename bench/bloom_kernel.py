#!/usr/bin/env python3
"""Bloom blur taps and pyramid levels against an exact Gaussian, in double precision (CPU only).

Writes two CSV files into the folder given as the only argument:

taps.csv   -- a separable blur of 2r+1 taps with weights exp(-k^2 / (2 sigma^2)) normalised over
              the taps (06-bloom's formula), sigma = 1.5 texels, r = 1..7, against the untruncated
              Gaussian of the same sigma at the texel centres: L1 distance (the tail the taps
              leave out plus the renormalisation that puts it back in the middle), the largest
              weight error, the variance error (texels^2), and texture reads per output pixel per
              direction. The row r = 3 is the reference's; its hard-coded
              c_weights are checked against the formula here (max_shader_weight_error).
levels.csv -- the pyramid as 06-bloom runs it (each level's first pass reads the image twice its
              size at its own texel steps, bilinear, so it also box-filters 2:1): the effective
              1D impulse response of each level along x (the direction blurred while
              downsampling) and y (blurred after), measured in full-resolution pixels and
              averaged over the 2^(L+1) sub-texel phases of the impulse, against a Gaussian of
              the same variance: effective sigma, L1 shape error, and how far the response's
              centre moves with the impulse's phase (shift variance, pixels). Cost: texture reads
              per full-resolution pixel for all levels up to this one.

References: Gaussian blur as a separable filter (Szeliski, Computer Vision: Algorithms and
Applications, 2nd ed. 2022, sec. 3.2); the normal CDF via math.erf.
"""
import math
import re
import sys
from pathlib import Path

SIGMA = 1.5


def phi(x):
    return 0.5 * (1.0 + math.erf(x / math.sqrt(2.0)))


def tap_weights(radius, sigma=SIGMA):
    w = [math.exp(-k * k / (2.0 * sigma * sigma)) for k in range(-radius, radius + 1)]
    s = sum(w)
    return [v / s for v in w]


def exact_weights(extent, sigma=SIGMA):
    """The untruncated Gaussian at texel centres -extent..extent (the rest is < 1e-15),
    normalised over all of them: what the taps approximate."""
    w = {k: math.exp(-k * k / (2.0 * sigma * sigma)) for k in range(-extent, extent + 1)}
    s = sum(w.values())
    return {k: v / s for k, v in w.items()}


def shader_weights(root):
    text = (Path(root) / "reference_solutions/06-bloom/blur.frag").read_text()
    m = re.search(r"c_weights\[\d+\]\s*=\s*float\[\d+\]\(([^)]*)\)", text)
    return [float(v) for v in m.group(1).split(",")] if m else None


def taps_table(root):
    rows = []
    exact = exact_weights(40)
    exact_var = sum(v * k * k for k, v in exact.items())
    shader = shader_weights(root)
    for r in range(1, 8):
        w = tap_weights(r)
        l1 = sum(abs((w[k + r] if -r <= k <= r else 0.0) - e) for k, e in exact.items())
        worst = max(abs((w[k + r] if -r <= k <= r else 0.0) - e) for k, e in exact.items())
        var = sum(v * (k - r) ** 2 for k, v in enumerate(w))
        shader_err = ""
        if r == 3 and shader:
            shader_err = "%.3g" % max(abs(shader[k] - w[r + k]) for k in range(4))
        rows.append((2 * r + 1, r, l1, worst, var - exact_var, 2 * r + 1, shader_err))
    return rows


def sample_linear(values, spacing, pos):
    """Bilinear (1D) lookup of a grid with texel centres at (j + 0.5) * spacing, clamped."""
    t = pos / spacing - 0.5
    j = math.floor(t)
    f = t - j
    n = len(values)
    a = values[min(max(j, 0), n - 1)]
    b = values[min(max(j + 1, 0), n - 1)]
    return a * (1.0 - f) + b * f


def run_axis(impulse_at, size, levels, blur_in_first_pass):
    """One axis of the chain, full resolution `size`, impulse at pixel `impulse_at`. Returns the
    output grid (values, spacing in full-res pixels) of each level. As lab.json declares it, the
    first (horizontal) pass of a level keeps its input's size and the second (vertical) pass
    writes an image half as large; both step one texel of their input. `blur_in_first_pass`: this
    axis is the first pass's direction (x)."""
    w = tap_weights(3)
    grid, spacing = [0.0] * size, 1.0
    grid[impulse_at] = 1.0
    out = []
    for _ in range(levels):
        # First pass: same size, taps along this axis only when it is the pass's direction.
        if blur_in_first_pass:
            first = [sum(w[idx] * sample_linear(grid, spacing, (i + 0.5) * spacing + k * spacing)
                         for idx, k in enumerate(range(-3, 4))) for i in range(len(grid))]
        else:
            first = grid
        # Second pass: half the size; each output centre sits between two input texels, so the
        # bilinear taps average pairs; taps along this axis only when it is the pass's direction.
        new_spacing = spacing * 2.0
        taps = [0] if blur_in_first_pass else range(-3, 4)
        weights = [1.0] if blur_in_first_pass else w
        second = []
        for i in range(len(first) // 2):
            c = (i + 0.5) * new_spacing
            second.append(sum(weights[idx] * sample_linear(first, spacing, c + k * spacing)
                              for idx, k in enumerate(taps)))
        grid, spacing = second, new_spacing
        out.append((grid, spacing))
    return out


def gaussian_shape_error(values, spacing):
    total = sum(values)
    if total <= 0:
        return float("nan"), float("nan"), float("nan")
    xs = [(i + 0.5) * spacing for i in range(len(values))]
    p = [v / total for v in values]
    mu = sum(x * q for x, q in zip(xs, p))
    var = sum((x - mu) ** 2 * q for x, q in zip(xs, p))
    # The Gaussian of the same mean and variance, integrated over each output texel (width
    # `spacing`): what an ideal blur of that width would put there.
    s = math.sqrt(var - spacing * spacing / 12.0) if var > spacing * spacing / 12.0 else math.sqrt(var)
    g = [phi((x + spacing / 2 - mu) / s) - phi((x - spacing / 2 - mu) / s) for x in xs]
    return math.sqrt(var), sum(abs(a - b) for a, b in zip(p, g)), mu


def levels_table(max_levels=4, size=512):
    rows = []
    reads = 0.0
    for level in range(max_levels):
        # texture reads per full-res pixel: 7 taps over (1/4)^level of the pixels (the horizontal
        # pass, at its input's size) and 7 over (1/4)^(level+1) (the vertical pass, halving)
        reads += 7 * 0.25 ** level + 7 * 0.25 ** (level + 1)
        for axis, blur_first in (("x", True), ("y", False)):
            step = 2 ** (level + 1)
            sigmas, errors, centres = [], [], []
            for phase in range(step):
                impulse = size // 2 + phase
                grid, spacing = run_axis(impulse, size, level + 1, blur_first)[level]
                sigma, err, mu = gaussian_shape_error(grid, spacing)
                sigmas.append(sigma)
                errors.append(err)
                centres.append(mu - (impulse + 0.5))
            rows.append((level, axis, sum(sigmas) / len(sigmas), sum(errors) / len(errors),
                         max(centres) - min(centres), reads))
    return rows


def main():
    out = Path(sys.argv[1])
    root = Path(__file__).resolve().parent.parent
    out.mkdir(parents=True, exist_ok=True)
    with open(out / "taps.csv", "w") as f:
        f.write("taps,radius,l1_error,max_weight_error,variance_error,reads_per_pixel_per_direction,"
                "max_shader_weight_error\n")
        for row in taps_table(root):
            f.write("%d,%d,%.6g,%.6g,%.6g,%d,%s\n" % row)
    with open(out / "levels.csv", "w") as f:
        f.write("level,axis,effective_sigma_px,l1_shape_error,centre_shift_px,texture_reads_per_pixel\n")
        for row in levels_table():
            f.write("%d,%s,%.4f,%.5f,%.4f,%.4f\n" % row)


if __name__ == "__main__":
    main()
