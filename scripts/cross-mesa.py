#!/usr/bin/env python3
"""Per lab, how far a report.json's images are from the goldens they were graded against: the
worst PSNR, SSIM, FLIP mean and mismatch fraction over every graded image, each beside its
threshold, and how many images are bit-identical. For `shaderlab grade reference_solutions
--no-reference` run on one Mesa against goldens drawn by another (docs/grading.md, "Renderers").
Usage: python3 scripts/cross-mesa.py REPORT.json"""
import json
import sys


def main(path):
    report = json.load(open(path))
    print("renderer: %s" % report.get("renderer", "?"))
    print("| lab | score | images | identical | worst PSNR (min) | worst SSIM (min) | worst FLIP mean (max) | worst mismatch (max) |")
    print("|---|---|---|---|---|---|---|---|")
    for lab in report["labs"]:
        n = same = 0
        psnr = ssim = flip = mism = None
        limits = {}
        for scene in lab["scenes"]:
            for p in scene["passes"]:
                m, t = p["metrics"], p["thresholds"]
                n += 1
                if m.get("identical"):
                    same += 1
                    continue
                if m.get("psnr_db") is not None and (psnr is None or m["psnr_db"] < psnr[0]):
                    psnr = (m["psnr_db"], t.get("psnr_min_db"))
                if m.get("ssim") is not None and (ssim is None or m["ssim"] < ssim[0]):
                    ssim = (m["ssim"], t.get("ssim_min"))
                if flip is None or m["flip_mean"] > flip[0]:
                    flip = (m["flip_mean"], t.get("flip_mean_max"))
                if mism is None or m["mismatch_fraction"] > mism[0]:
                    mism = (m["mismatch_fraction"], t.get("mismatch_max"))

        def cell(v, digits):
            if v is None:
                return "-"
            limit = "?" if v[1] is None else ("%." + str(digits) + "f") % v[1]
            return ("%." + str(digits) + "f (%s)") % (v[0], limit)

        print("| %s | %g / %g | %d | %d | %s | %s | %s | %s |" % (
            lab["id"], lab["score"], lab["max_score"], n, same, cell(psnr, 1), cell(ssim, 4),
            cell(flip, 4), cell(mism, 4)))


if __name__ == "__main__":
    main(sys.argv[1])
