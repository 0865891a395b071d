#!/usr/bin/python3
"""The browser workbench (`shaderlab serve`) as a student sees it: headless Chromium over the
DevTools protocol (cdp.py) on a page served for a copy of a reference solution (serve_fixture.py).

What is checked: the picture on the page is, pixel for pixel, the picture `shaderlab render` writes
(read back from the canvas and from a real screenshot); saves (by rename and by truncate-then-write)
change the picture without reloading the page; a broken shader shows file, line, source and caret
while the last good picture stays; a hanging shader is reported as timed out (or as an endless
loop) while the page and the server keep answering; two tabs follow the same saves; the pixel inspector and the turned camera.

Run: /usr/bin/python3 tests/serve/serve_browser_test.py --shaderlab build/framework/shaderlab --source .
Exits 77 (CTest's skip) where chromium or python3-websocket is missing."""
import base64
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import threading
import time
import unittest
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import serve_fixture  # noqa: E402
from serve_fixture import Served  # noqa: E402

ARGS = None  # set in main()
LAB = "01-phong"
GOOD_LINE = "o_color = vec4(color, 1.0);"


# ---- PNG (ISO/IEC 15948): 8-bit grey, grey+alpha, RGB or RGBA, not interlaced ----

def _paeth(a, b, c):
    p = a + b - c
    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
    if pa <= pb and pa <= pc:
        return a
    return b if pb <= pc else c


def decode_png(data):
    """Returns (width, height, rows): rows[y] is a bytes of width*3 RGB values (alpha dropped)."""
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("not a PNG")
    pos, ihdr, idat = 8, None, []
    while pos + 8 <= len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if zlib.crc32(kind + body) & 0xFFFFFFFF != struct.unpack(">I", data[pos + 8 + length:pos + 12 + length])[0]:
            raise ValueError("bad CRC in chunk %r" % kind)
        pos += 12 + length
        if kind == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat.append(body)
        elif kind == b"IEND":
            break
    if not ihdr:
        raise ValueError("no IHDR")
    width, height, depth, colour, _, _, interlace = ihdr
    channels = {0: 1, 2: 3, 4: 2, 6: 4}.get(colour)
    if depth != 8 or channels is None or interlace != 0:
        raise ValueError("unsupported PNG: depth %d colour type %d interlace %d" % (depth, colour, interlace))
    raw = zlib.decompress(b"".join(idat))
    bpp, stride = channels, width * channels
    if len(raw) < height * (stride + 1):
        raise ValueError("short image data")
    prev = bytearray(stride)
    rows = []
    for y in range(height):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        if f == 1:
            for i in range(bpp, stride):
                line[i] = (line[i] + line[i - bpp]) & 0xFF
        elif f == 2:
            for i in range(stride):
                line[i] = (line[i] + prev[i]) & 0xFF
        elif f == 3:
            for i in range(stride):
                left = line[i - bpp] if i >= bpp else 0
                line[i] = (line[i] + ((left + prev[i]) >> 1)) & 0xFF
        elif f == 4:
            for i in range(stride):
                left = line[i - bpp] if i >= bpp else 0
                upleft = prev[i - bpp] if i >= bpp else 0
                line[i] = (line[i] + _paeth(left, prev[i], upleft)) & 0xFF
        elif f != 0:
            raise ValueError("bad filter type %d in row %d" % (f, y))
        prev = line
        if channels == 3:
            rgb = bytes(line)
        elif channels == 4:
            rgb = bytes(b for i, b in enumerate(line) if i % 4 != 3)
        else:
            grey = line[::channels]
            rgb = bytes(v for g in grey for v in (g, g, g))
        rows.append(rgb)
    return width, height, rows


def differing_pixels(a, b):
    """Counts the pixels whose RGB differ between two decoded PNGs of the same size; returns
    (count, first differing (x, y, a_rgb, b_rgb) or None)."""
    wa, ha, ra = a
    wb, hb, rb = b
    if (wa, ha) != (wb, hb):
        raise AssertionError("sizes differ: %dx%d and %dx%d" % (wa, ha, wb, hb))
    count, first = 0, None
    for y in range(ha):
        if ra[y] == rb[y]:
            continue
        for x in range(wa):
            pa, pb = ra[y][3 * x:3 * x + 3], rb[y][3 * x:3 * x + 3]
            if pa != pb:
                count += 1
                if first is None:
                    first = (x, y, tuple(pa), tuple(pb))
    return count, first


class PngDecoderTest(unittest.TestCase):
    """The decoder the comparisons rely on, on PNGs made here with every filter type."""

    @staticmethod
    def encode(width, height, pixels, channels, filters):
        def chunk(kind, body):
            return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)
        stride, bpp = width * channels, channels
        raw, prev = bytearray(), bytearray(stride)
        for y in range(height):
            line = pixels[y * stride:(y + 1) * stride]
            f = filters[y % len(filters)]
            out = bytearray(stride)
            for i in range(stride):
                left = line[i - bpp] if i >= bpp else 0
                up = prev[i]
                upleft = prev[i - bpp] if i >= bpp else 0
                pred = [0, left, up, (left + up) >> 1, _paeth(left, up, upleft)][f]
                out[i] = (line[i] - pred) & 0xFF
            raw += bytes([f]) + out
            prev = bytearray(line)
        colour = {3: 2, 4: 6}[channels]
        return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, colour, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(bytes(raw))) + chunk(b"IEND", b""))

    def test_all_five_filters_rgb_and_rgba(self):
        w, h = 7, 10
        for channels in (3, 4):
            pixels = bytes((x * 37 + y * 91 + c * 53 + (x * y) % 17) & 0xFF
                           for y in range(h) for x in range(w) for c in range(channels))
            png = self.encode(w, h, pixels, channels, [0, 1, 2, 3, 4])
            dw, dh, rows = decode_png(png)
            self.assertEqual((dw, dh), (w, h))
            want = [bytes(pixels[(y * w + x) * channels + c] for x in range(w) for c in range(3)) for y in range(h)]
            self.assertEqual(rows, want, "channels %d" % channels)


# ---- the server and the page ----

JS_PAGE_READY = "!!(window.workbench && document.getElementById('picture'))"


def canvas_png(page):
    url = page.eval("document.getElementById('picture').toDataURL('image/png')")
    assert url.startswith("data:image/png;base64,"), url[:40]
    return base64.b64decode(url.split(",", 1)[1])


def centre_pixel(page):
    return page.eval("(() => { const c = document.getElementById('picture');"
                     " const d = c.getContext('2d').getImageData(c.width >> 1, c.height >> 1, 1, 1).data;"
                     " return [d[0], d[1], d[2]]; })()")


def close_to(rgb, want, tol=1):
    return rgb is not None and all(abs(a - b) <= tol for a, b in zip(rgb, want))


def replace_output(frag, new):
    """phong.frag with its final output line replaced."""
    assert GOOD_LINE in frag, "the reference phong.frag no longer ends with %r" % GOOD_LINE
    return frag.replace(GOOD_LINE, new)


def settled(st):
    """The server has shown and judged the newest picture, with nothing left to do."""
    p = st.get("picture")
    return bool(p) and p.get("judged") and not st.get("busy") and st.get("grade") and \
        st["grade"].get("lab") and not st["grade"].get("pending")


class BrowserTest(unittest.TestCase):
    browser = None

    @classmethod
    def setUpClass(cls):
        import cdp
        cls.browser = cdp.Browser()
        # Chromium's messages after start-up, read so that a full pipe never stalls it.
        cls.drain = threading.Thread(target=lambda: [None for _ in cls.browser.proc.stderr], daemon=True)
        cls.drain.start()

    @classmethod
    def tearDownClass(cls):
        if cls.browser:
            cls.browser.close()
            cls.drain.join(10)
            cls.browser.proc.stderr.close()

    def setUp(self):
        self.pages = []

    def tearDown(self):
        for p in self.pages:
            p.close()

    def open(self, s, scale=None):
        page = self.browser.new_page(s.url)
        self.pages.append(page)
        page.wait_for(JS_PAGE_READY, 20, "the page's script")
        if scale is not None:
            page.eval("(() => { const s = document.getElementById('scale'); s.value = '%d';"
                      " s.dispatchEvent(new Event('change')); return true; })()" % scale)
        page.wait_for("window.workbench.shownSeq > 0", 30, "a first picture on the page")
        return page

    def wait_picture(self, page, s, timeout=30):
        """Waits until the page shows the server's newest picture at its own size; returns the
        state."""
        deadline = time.time() + timeout
        while True:
            st = s.state()
            p = st["picture"]
            if p:
                img = p["images"][p["final_image"]]
                got = page.eval("[window.workbench.shownSeq, document.getElementById('picture').width,"
                                " document.getElementById('picture').height, window.workbench.shownKey]")
                scale = int(page.eval("document.getElementById('scale').value"))
                if got[0] == p["seq"] and got[1] == img["width"] * scale and got[2] == img["height"] * scale:
                    return st
            if time.time() > deadline:
                self.fail("the page did not show picture %s (page: %r)" % (p and p["seq"], got if p else None))
            time.sleep(0.05)

    # 1
    def test_1_picture_equals_headless_render(self):
        with Served(ARGS, LAB) as s:
            page = self.open(s, scale=1)
            st = s.wait_state(settled, 60, "the first picture judged and the lab graded")
            st = self.wait_picture(page, s)
            p = st["picture"]
            img = p["images"][p["final_image"]]
            self.assertTrue(img["graded"])
            self.assertTrue(p["graded_view"])
            scene = st["view"]["scene"]
            self.assertEqual(scene, st["scenes"][0])

            out = tempfile.mkdtemp(prefix="shaderlab-render-")
            try:
                r = subprocess.run([ARGS.shaderlab, "render", s.root, "--lab", LAB, "--labs",
                                    os.path.join(ARGS.source, "labs"), "--out", out],
                                   stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=120)
                self.assertEqual(r.returncode, 0, r.stdout)
                path = os.path.join(out, LAB, scene + ".png")
                self.assertTrue(os.path.isfile(path), "render wrote no %s:\n%s" % (path, r.stdout))
                with open(path, "rb") as f:
                    want = decode_png(f.read())
            finally:
                shutil.rmtree(out, ignore_errors=True)
            self.assertEqual((want[0], want[1]), (img["width"], img["height"]))

            # The server's own PNG, the canvas and a screenshot of it: each the rendered picture.
            served = decode_png(s.get("/picture/%d/student/%d.png" % (p["seq"], img["index"]))[1])
            n, first = differing_pixels(served, want)
            self.assertEqual(n, 0, "the served PNG differs from `render`'s in %d pixels (first %r)" % (n, first))

            on_canvas = decode_png(canvas_png(page))
            n, first = differing_pixels(on_canvas, want)
            self.assertEqual(n, 0, "the canvas differs from `render`'s PNG in %d pixels (first: x, y, canvas, "
                                   "render = %r)" % (n, first))

            rect = page.eval("(() => { const r = document.getElementById('picture').getBoundingClientRect();"
                             " return {x: r.left + window.scrollX, y: r.top + window.scrollY,"
                             " width: r.width, height: r.height, vw: window.innerWidth, vh: window.innerHeight}; })()")
            self.assertEqual((rect["width"], rect["height"]), (img["width"], img["height"]), rect)
            self.assertLessEqual(rect["y"] + rect["height"], rect["vh"], "the canvas is not all in view: %r" % rect)
            shot = decode_png(page.screenshot(
                {"x": rect["x"], "y": rect["y"], "width": rect["width"], "height": rect["height"]}))
            n, first = differing_pixels(shot, want)
            self.assertEqual(n, 0, "the screenshot of the canvas differs from `render`'s PNG in %d pixels "
                                   "(first: x, y, screen, render = %r)" % (n, first))

    # 2
    def test_2_saves_change_the_picture_without_reload(self):
        with Served(ARGS, LAB) as s:
            page = self.open(s)
            s.wait_state(settled, 60, "the first picture judged")
            self.wait_picture(page, s)
            before = centre_pixel(page)
            loads = page.eval("window.workbench.loads")
            page.eval("window.__marker = 42")
            seq0 = page.eval("window.workbench.shownSeq")
            good = s.read("phong.frag")

            # By rename: a constant colour (0.2, 0.8, 0.4) -> 8-bit (51, 204, 102).
            green = (51, 204, 102)
            self.assertFalse(close_to(before, green, 8), "the centre was already %r" % (before,))
            s.save("phong.frag", replace_output(good, "o_color = vec4(0.2, 0.8, 0.4, 1.0);"), how="rename")
            page.wait_for("window.workbench.shownSeq > %d" % seq0, 30, "a new picture after the rename")
            deadline = time.time() + 30
            while not close_to(centre_pixel(page), green) and time.time() < deadline:
                time.sleep(0.05)
            self.assertTrue(close_to(centre_pixel(page), green),
                            "centre %r after the save, want %r" % (centre_pixel(page), green))
            self.assertEqual(page.eval("window.__marker"), 42, "the page reloaded")
            self.assertGreater(page.eval("window.workbench.loads"), loads)

            # Truncate, then write a moment later (as some editors save); record whether the page
            # ever shows an error meanwhile (it must not: the half-written file is never rendered).
            page.eval("window.__errors = 0; window.__watch = setInterval(() => {"
                      " if (!document.getElementById('error').classList.contains('hidden')) window.__errors++; }, 5);"
                      " true")
            seq1 = page.eval("window.workbench.shownSeq")
            pink = (204, 51, 153)
            path = os.path.join(s.lab_dir, "phong.frag")
            with open(path, "w"):
                pass
            with open(path, "w") as f:
                f.write(replace_output(good, "o_color = vec4(0.8, 0.2, 0.6, 1.0);"))
            page.wait_for("window.workbench.shownSeq > %d" % seq1, 30, "a new picture after truncate-then-write")
            deadline = time.time() + 30
            while not close_to(centre_pixel(page), pink) and time.time() < deadline:
                time.sleep(0.05)
            self.assertTrue(close_to(centre_pixel(page), pink),
                            "centre %r after the truncate-then-write save, want %r" % (centre_pixel(page), pink))
            st = s.wait_state(lambda x: not x["busy"], 30, "the server idle")
            self.assertIsNone(st["error"], "the save left an error: %r" % (st["error"],))
            self.assertEqual(page.eval("clearInterval(window.__watch); window.__errors"), 0,
                             "the page showed an error during the truncate-then-write save")
            self.assertEqual(page.eval("window.__marker"), 42, "the page reloaded")

    # 3
    def test_3_broken_shader_shows_file_line_and_caret(self):
        with Served(ARGS, LAB) as s:
            page = self.open(s)
            s.wait_state(settled, 60, "the first picture judged")
            self.wait_picture(page, s)
            good = s.read("phong.frag")
            lines = good.split("\n")
            target = "vec3 n = normalize(v_world_normal);"
            n = next(i for i, l in enumerate(lines) if l.strip() == target) + 1  # 1-based
            broken = lines[:]
            broken[n - 1] = broken[n - 1].replace(target, target[:-1])  # drop the ';'
            seq = page.eval("window.workbench.shownSeq")
            centre_before = centre_pixel(page)
            s.save("phong.frag", "\n".join(broken))

            page.wait_for("!document.getElementById('error').classList.contains('hidden')"
                          " && document.getElementById('error-diagnostics').textContent.length > 0",
                          30, "the error box")
            st = s.state()
            err = st["error"]
            self.assertIsNotNone(err)
            diags = [d for d in err["diagnostics"] if d["severity"] == "error"]
            self.assertTrue(diags, "no error diagnostics: %r" % (err,))
            d = diags[0]
            self.assertEqual(os.path.basename(d["file"]), "phong.frag", d)
            # The missing ';' is noticed on its line or at the start of the next.
            self.assertIn(d["line"], (n, n + 1), "want line %d or %d: %r" % (n, n + 1, d))
            shown = page.eval("document.getElementById('error').innerText")
            where = "phong.frag:%d" % d["line"]
            self.assertIn(where, shown, shown)
            # The source line as saved, under its number, then a caret line.
            self.assertIn("%d | %s" % (d["line"], broken[d["line"] - 1]), shown, shown)
            pres = page.eval("[...document.querySelectorAll('#error-diagnostics pre')].map(e => e.textContent)")
            self.assertTrue(any(l.strip().startswith("|") and l.rstrip().endswith("^")
                                for pre in pres for l in pre.split("\n")), "no caret line in %r" % pres)
            self.assertIn("compile", page.eval("document.getElementById('error-title').textContent").lower())
            self.assertIn("last good picture", page.eval("document.getElementById('error-note').textContent"))

            # The last good picture stays.
            self.assertEqual(st["picture"]["seq"], seq)
            self.assertEqual(page.eval("window.workbench.shownSeq"), seq)
            self.assertEqual(centre_pixel(page), centre_before)
            distinct = page.eval("(() => { const c = document.getElementById('picture');"
                                 " const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;"
                                 " const s = new Set(); for (let i = 0; i < d.length; i += 4 * 97)"
                                 " s.add(d[i] + ',' + d[i + 1] + ',' + d[i + 2]); return s.size; })()")
            self.assertGreater(distinct, 10, "the canvas looks blank")

            # Mended: the error goes and a new picture comes.
            s.save("phong.frag", good)
            page.wait_for("document.getElementById('error').classList.contains('hidden')"
                          " && window.workbench.shownSeq > %d" % seq, 30, "the error gone and a new picture")
            self.assertEqual(page.eval("window.workbench.errorShown"), "")
            self.assertIsNone(s.state()["error"])

    # 4
    def test_4_hanging_shader_is_stopped_page_stays_responsive(self):
        with Served(ARGS, LAB, extra=["--view-timeout", "2", "--timeout", "3"]) as s:
            page = self.open(s)
            s.wait_state(settled, 60, "the first picture judged")
            self.wait_picture(page, s)
            seq = page.eval("window.workbench.shownSeq")
            good = s.read("phong.frag")
            # A loop whose end depends on a uniform the compiler cannot see through (as the
            # viewer's test hangs).
            s.save("phong.frag", replace_output(
                good, "float k = 0.0; while (k >= 0.0) { k += u_ambient + 1.0; } o_color = vec4(color * k, 1.0);"))
            st = s.wait_state(lambda x: x["busy"].startswith("rendering your shaders"), 20,
                              "the hanging render under way")

            # While it hangs: the state answers quickly from the page, and the buttons work.
            ms = page.eval("(async () => { const t = performance.now();"
                           " const r = await fetch('/api/state', {cache: 'no-store'}); const j = await r.json();"
                           " return [performance.now() - t, j.busy]; })()")
            self.assertLess(ms[0], 1000, "fetch('/api/state') took %.0f ms during the hang" % ms[0])
            self.assertTrue(ms[1].startswith("rendering your shaders"), "the hang was over already: %r" % ms)
            t0 = time.time()
            toggled = page.eval("(() => { const b = document.getElementById('mode-reference'); b.click();"
                                " return b.classList.contains('on') &&"
                                " !document.getElementById('mode-student').classList.contains('on'); })()")
            self.assertTrue(toggled, "the reference button did not turn on")
            self.assertLess(time.time() - t0, 1.0)
            self.assertTrue(s.state()["busy"].startswith("rendering your shaders"),
                            "the checks above did not run during the hang")
            page.eval("document.getElementById('mode-student').click(); true")

            # Whichever stops it first, the clock ("Timed out") or, on a fast machine, the loop guard
            # ("Endless loop", serve_workbench_test.py), names the shader, pass and scene.
            title = page.wait_for("(() => { const t = document.getElementById('error-title').textContent;"
                                  " return t.includes('Timed out') || t.includes('Endless loop') ? t : ''; })()",
                                  30, "the stop shown")
            scene = st["view"]["scene"]
            self.assertIn("phong.frag", title)
            self.assertIn("pass 'shade'", title)
            self.assertIn("scene " + scene, title)
            err = s.state()["error"]
            self.assertEqual(err["scene"], scene)
            self.assertEqual(err["endless_loop"], err["title"].startswith("Endless loop"), err["title"])
            self.assertEqual(page.eval("window.workbench.shownSeq"), seq, "the last good picture was replaced")

    # 5
    def test_5_two_tabs_follow_the_same_saves(self):
        with Served(ARGS, LAB) as s:
            a = self.open(s)
            b = self.open(s)
            st = s.wait_state(settled, 60, "the first picture judged")
            self.wait_picture(a, s)
            self.wait_picture(b, s)
            seq = st["picture"]["seq"]
            s.save("phong.frag", replace_output(s.read("phong.frag"), "o_color = vec4(color.bgr, 1.0);"))
            st = s.wait_state(lambda x: x["picture"]["seq"] > seq and not x["busy"].startswith("rendering"),
                              30, "a new picture")
            new = st["picture"]["seq"]
            for name, page in (("first", a), ("second", b)):
                got = page.wait_for("window.workbench.shownSeq >= %d && window.workbench.shownSeq" % new, 30,
                                    "the %s tab's picture %d" % (name, new))
                self.assertEqual(got, s.state()["picture"]["seq"], "the %s tab" % name)
            self.assertEqual(a.eval("window.workbench.shownSeq"), b.eval("window.workbench.shownSeq"))
            self.assertEqual(canvas_png(a) == canvas_png(b), True, "the tabs show different pixels")

    # 6
    def test_6_pixel_inspector_and_turned_view(self):
        with Served(ARGS, LAB) as s:
            page = self.open(s)
            st = s.wait_state(settled, 60, "the first picture judged")
            self.wait_picture(page, s)
            p = st["picture"]
            self.assertTrue(p["images"][p["final_image"]]["has_reference"])
            page.eval("(() => { const c = document.getElementById('picture'); const r = c.getBoundingClientRect();"
                      " c.dispatchEvent(new MouseEvent('mousemove', {bubbles: true,"
                      " clientX: Math.ceil(r.left + r.width / 2 + 0.5), clientY: Math.ceil(r.top + r.height / 2 + 0.5)})); return true; })()")
            text = page.wait_for("(() => { const t = document.getElementById('inspector').textContent;"
                                 " return t.includes('yours') ? t : ''; })()", 10, "the inspector")
            img = p["images"][p["final_image"]]
            self.assertIn("(%d, %d)" % (img["width"] // 2, img["height"] // 2), text)
            self.assertIn("reference", text)
            self.assertIn("FLIP", text)
            yours = text.split("yours", 1)[1].split("reference", 1)[0].split()
            ref = text.split("reference", 1)[1].split("FLIP", 1)[0].split()
            flip = text.split("FLIP", 1)[1].split()
            self.assertEqual(len(yours), 4, text)
            self.assertEqual(yours, ref, "the reference solution differs from itself: %s" % text)
            self.assertEqual(flip, ["0.000"], text)
            # The values are the picture's: the centre pixel on the canvas, in 0..255.
            rgb = centre_pixel(page)
            for v, c in zip(yours[:3], rgb):
                self.assertLessEqual(abs(round(min(max(float(v), 0.0), 1.0) * 255) - c), 1, (text, rgb))

            seq = st["picture"]["seq"]
            before = canvas_png(page)
            r = page.eval("(async () => { const r = await fetch('/api/view', {method: 'POST',"
                          " headers: {'Content-Type': 'application/json'},"
                          " body: JSON.stringify({scene: '%s', yaw: 40, pitch: 0, zoom: 1})});"
                          " return [r.status, await r.json()]; })()" % st["view"]["scene"])
            self.assertEqual(r[0], 200, r)
            st = s.wait_state(lambda x: x["picture"]["seq"] > seq and not x["picture"]["graded_view"], 30,
                              "a picture of the turned view")
            self.assertAlmostEqual(st["picture"]["orbit"]["yaw"], 40)
            self.assertIsNone(st["picture"]["scene_passed"])
            page.wait_for("window.workbench.shownSeq >= %d" % st["picture"]["seq"], 30, "the turned picture shown")
            note = page.wait_for("(() => { const t = document.getElementById('view-note').textContent;"
                                 " return t.includes('turned view') ? t : ''; })()", 10, "the view note")
            self.assertIn("yaw 40", note)
            self.assertFalse(page.eval("document.getElementById('reset-view').classList.contains('hidden')"))
            self.assertNotEqual(canvas_png(page), before, "the turned view shows the same pixels")

            # Back to the graded view with the page's button.
            page.eval("document.getElementById('reset-view').click(); true")
            page.wait_for("document.getElementById('view-note').textContent.includes('graded view')", 30,
                          "the graded view again")
            st = s.wait_state(lambda x: x["picture"]["graded_view"], 30, "a picture of the graded view")
            self.assertTrue(st["view"]["graded_view"])

    # 7
    def test_7_debug_view_of_the_vertex_data(self):
        """The page's "vertex data" select asks the server for a debug view (nothing is computed in
        the page): the canvas is `render --debug`'s PNG, the notes say which mesh has no tangents,
        the inspector reads the normal the server decodes, and a mode button brings the lab's
        picture back."""
        with Served(ARGS, LAB) as s:
            page = self.open(s, scale=1)
            st = s.wait_state(settled, 60, "the first picture judged and the lab graded")
            st = self.wait_picture(page, s)
            scene = st["view"]["scene"]
            lab_canvas = canvas_png(page)
            names = page.eval("[...document.getElementById('debug').options].map(o => o.value)")
            self.assertEqual(names, ["off"] + [v["name"] for v in st["debug_views"]])
            self.assertIn("tangents", names)

            def pick(name):
                page.eval("(() => { const s = document.getElementById('debug'); s.value = '%s';"
                          " s.dispatchEvent(new Event('change')); return true; })()" % name)
                d = s.wait_state(lambda x: x["view"]["debug"] == name and x["debug"] and
                                 x["debug"]["view"] == name and x["debug"]["scene"] == scene, 30,
                                 "the %s view drawn" % name)["debug"]
                page.wait_for("window.workbench.shownDebugSeq === %d" % d["seq"], 30, "the %s view shown" % name)
                return d

            d = pick("normals")
            self.assertEqual(d["notes"], [])
            label = page.eval("document.getElementById('picture-label').textContent")
            self.assertIn("vertex data: normals", label)
            self.assertIn("not graded", page.eval("document.getElementById('verdict-summary').textContent"))
            out = tempfile.mkdtemp(prefix="shaderlab-render-debug-")
            try:
                r = subprocess.run([ARGS.shaderlab, "render", "--lab", LAB, "--labs", os.path.join(ARGS.source, "labs"),
                                    "--debug", "normals", "--out", out],
                                   stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=120)
                self.assertEqual(r.returncode, 0, r.stdout)
                with open(os.path.join(out, LAB, scene + ".debug-normals.png"), "rb") as f:
                    want = decode_png(f.read())
            finally:
                shutil.rmtree(out, ignore_errors=True)
            n, first = differing_pixels(decode_png(canvas_png(page)), want)
            self.assertEqual(n, 0, "the canvas differs from `render --debug`'s PNG in %d pixels (first %r)" % (n, first))

            # The inspector: the server says what the centre pixel stands for.
            page.eval("(() => { const c = document.getElementById('picture'); const r = c.getBoundingClientRect();"
                      " c.dispatchEvent(new MouseEvent('mousemove', {bubbles: true,"
                      " clientX: Math.ceil(r.left + r.width / 2 + 0.5), clientY: Math.ceil(r.top + r.height / 2 + 0.5)})); return true; })()")
            text = page.wait_for("(() => { const t = document.getElementById('inspector').textContent;"
                                 " return t.includes('normal (') ? t : ''; })()", 10, "the inspector")
            normal = [float(v) for v in text.split("normal (", 1)[1].split(")", 1)[0].split(",")]
            self.assertGreater(normal[2], 0.9, "the sphere's centre faces the camera: %s" % text)

            d = pick("tangents")
            self.assertTrue(any(n.startswith("no tangents in scenes/") and "drawn grey" in n for n in d["notes"]), d)
            shown_notes = page.wait_for("(() => { const e = document.getElementById('debug-notes');"
                                        " return e.classList.contains('hidden') ? '' : e.textContent; })()", 10,
                                        "the notes on the page")
            self.assertIn("no tangents in scenes/", shown_notes)
            self.assertTrue(close_to(centre_pixel(page), (89, 89, 89)), "grey: %r" % (centre_pixel(page),))

            # A mode of the lab's picture turns the debug view off.
            page.eval("document.getElementById('mode-student').click(); true")
            s.wait_state(lambda x: x["view"]["debug"] == "off", 10, "the debug view off")
            page.wait_for("!window.workbench.shownKey.includes('/debug/')", 30, "the lab's picture again")
            self.assertEqual(canvas_png(page), lab_canvas, "the lab's picture is not back")
            self.assertTrue(page.eval("document.getElementById('debug-notes').classList.contains('hidden')"))


def main():
    def take(args):
        global ARGS
        ARGS = args
    return serve_fixture.run_browser_suite(take)


if __name__ == "__main__":
    sys.exit(main())
