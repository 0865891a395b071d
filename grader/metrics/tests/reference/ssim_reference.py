"""SSIM of the test pair (test_pair.py) by scikit-image, the value ssim_test.cpp expects.

Run: python3 grader/metrics/tests/reference/ssim_reference.py   (Debian: python3-skimage, 0.19.3 used)
"""
import numpy as np
from skimage.metrics import structural_similarity

from test_pair import test_pair

reference, test = test_pair()
value = structural_similarity(reference.astype(np.float64), test.astype(np.float64), gaussian_weights=True,
                              sigma=1.5, use_sample_covariance=False, data_range=1, channel_axis=-1)
print(f"{value:.10f}")
