"""Starts `shaderlab serve` for the workbench's tests: a copy of one lab's reference solution as the
student's folder (so a test may break and mend it), a free port, and the server's output kept.
Usage in a test: with Served(args, "01-phong") as s: s.url, s.lab_dir, s.save(name, text)."""
import argparse
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
import urllib.request

SKIP = 77  # CTest's SKIP_RETURN_CODE for these tests


def parse_args():
    ap = argparse.ArgumentParser()
    ap.add_argument("--shaderlab", required=True, help="the shaderlab program")
    ap.add_argument("--source", required=True, help="the source tree (labs/, reference_solutions/)")
    ap.add_argument("tests", nargs="*", help="unittest names (default: all)")
    return ap.parse_args()


def run_browser_suite(take_args):
    """The main of a suite that drives the page in Chromium: the arguments parsed and handed to
    take_args, skipped (CTest's 77, saying why) where python3-websocket or chromium is missing,
    then unittest over the tests named (all by default). Returns the exit code."""
    import unittest
    args = parse_args()
    args.shaderlab = os.path.abspath(args.shaderlab)
    args.source = os.path.abspath(args.source)
    take_args(args)
    try:
        import websocket  # noqa: F401
    except ImportError:
        print("skipped: the python3 websocket module (python3-websocket) is not installed")
        return SKIP
    import cdp
    if not cdp.find_chromium():
        print("skipped: no chromium to drive (install chromium)")
        return SKIP
    argv = [sys.argv[0]] + list(args.tests)
    prog = unittest.main(module="__main__", argv=argv, verbosity=2, exit=False)
    return 0 if prog.result.wasSuccessful() else 1


class Served:
    def __init__(self, args, lab, extra=(), submission=None):
        self.args = args
        self.lab = lab
        self.extra = list(extra)
        self.submission_src = submission
        self.output = []

    def __enter__(self):
        self.tmp = tempfile.mkdtemp(prefix="shaderlab-serve-")
        self.root = os.path.join(self.tmp, "work")
        src = self.submission_src or os.path.join(self.args.source, "reference_solutions", self.lab)
        shutil.copytree(src, os.path.join(self.root, self.lab))
        self.lab_dir = os.path.join(self.root, self.lab)
        cmd = [self.args.shaderlab, "serve", self.lab, "--submission", self.root, "--port", "0",
               "--labs", os.path.join(self.args.source, "labs")] + self.extra
        self.proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        self.started = time.time()
        self.port = None
        got_port = threading.Event()

        def read():
            for line in self.proc.stdout:
                self.output.append(line)
                m = re.search(r"open http://[^:]+:(\d+)/", line)
                if m and not self.port:
                    self.port = int(m.group(1))
                    self.address_printed = time.time()
                    got_port.set()
            got_port.set()

        self.reader = threading.Thread(target=read, daemon=True)
        self.reader.start()
        if not got_port.wait(30) or not self.port:
            self.__exit__(None, None, None)
            raise RuntimeError("serve did not print its address:\n" + "".join(self.output))
        self.url = "http://127.0.0.1:%d/" % self.port
        return self

    def __exit__(self, *exc):
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGINT)
            try:
                self.proc.wait(20)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        self.reader.join(10)
        self.proc.stdout.close()
        shutil.rmtree(self.tmp, ignore_errors=True)
        return False

    def save(self, name, text, how="rename"):
        """Saves a student file as an editor would: by rename (write a temporary file, rename it
        over the old one) or by truncate-then-write."""
        path = os.path.join(self.lab_dir, name)
        if how == "rename":
            tmp = path + ".tmp-save"
            with open(tmp, "w") as f:
                f.write(text)
            os.replace(tmp, path)
        else:
            with open(path, "w") as f:
                f.write(text)

    def read(self, name):
        with open(os.path.join(self.lab_dir, name)) as f:
            return f.read()

    def get(self, path, timeout=10):
        with urllib.request.urlopen(self.url.rstrip("/") + path, timeout=timeout) as r:
            return r.status, r.read()

    def state(self):
        import json
        return json.loads(self.get("/api/state")[1])

    def wait_state(self, predicate, timeout=60, what="a state"):
        deadline = time.time() + timeout
        s = None
        while time.time() < deadline:
            s = self.state()
            if predicate(s):
                return s
            time.sleep(0.05)
        raise TimeoutError("waited %.0f s for %s; last state busy=%r error=%r" %
                           (timeout, what, s and s.get("busy"), s and s.get("error")))

    def rss_kib(self):
        with open("/proc/%d/status" % self.proc.pid) as f:
            for line in f:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1])
        return 0
