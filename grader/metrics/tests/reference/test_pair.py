"""The deterministic image pair of grader/metrics/tests/test_images.h (patternImage, withNoise), rebuilt
bit for bit in numpy, for the scripts that produce the reference values the tests compare with.
"""
import numpy as np


def pattern_image(width, height, phase=0.0):
    y, x = np.mgrid[0:height, 0:width].astype(np.float64)
    channels = [0.5 + 0.3 * np.sin(0.37 * x + 0.11 * y * (c + 1) + phase) + 0.1 * np.cos(0.05 * x * y + c)
                for c in range(3)]
    return np.stack(channels, axis=-1).astype(np.float32)


def with_noise(image, amplitude, seed):
    out = image.copy()
    state = seed
    amplitude = np.float32(amplitude)
    for y in range(image.shape[0]):
        for x in range(image.shape[1]):
            for c in range(3):
                state = (state * 1664525 + 1013904223) % (1 << 32)
                r = np.float32(state >> 8) / np.float32(16777216.0)
                v = image[y, x, c] + amplitude * (np.float32(2.0) * r - np.float32(1.0))
                out[y, x, c] = min(np.float32(1.0), max(np.float32(0.0), v))
    return out


def test_pair():
    """64 x 48: the pattern, and the pattern with a phase shift plus noise of amplitude 0.05."""
    reference = pattern_image(64, 48)
    test = with_noise(pattern_image(64, 48, 0.4), 0.05, 1234)
    return reference, test
