#!/usr/bin/python3
"""The browser workbench (`shaderlab serve`) against hostile clients, over raw sockets so that nothing
tidies the bytes on the way: path traversal and absolute paths, a 1 MB header and 10,000 header
fields, 10,000 idle connections, a client that reads one byte a second, slowloris clients,
malformed requests and bodies, more event streams than allowed, the address it listens on, and a
second server on the same port.

Each test ends by asking the server for GET /api/state, which must come back promptly (200, JSON):
one server serves the whole class, and a test that leaves it stalled fails itself, not the next.
The limits tested are those of framework/serve/src/serve.cpp and connection_guard.h.

Run: /usr/bin/python3 tests/serve/serve_hostile_test.py --shaderlab build/framework/shaderlab --source .
Linux only: it reads TCP_INFO of its own sockets and /proc/net/tcp for the server's end of a
connection (to tell a socket the server closed from one its kernel has let go). Exits 77 (CTest's
skip) where the program is missing."""
import errno
import json
import os
import resource
import selectors
import socket
import subprocess
import sys
import threading
import time
import unittest
import urllib.request

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import serve_fixture  # noqa: E402
from serve_fixture import SKIP, Served  # noqa: E402

ARGS = None  # set in main()
LAB = "01-phong"
PROMPT_S = 5.0  # "promptly": a GET /api/state on a healthy server, with room for a slow machine

TCP_STATES = {1: "ESTABLISHED", 2: "SYN_SENT", 3: "SYN_RECV", 4: "FIN_WAIT1", 5: "FIN_WAIT2",
              6: "TIME_WAIT", 7: "CLOSE", 8: "CLOSE_WAIT", 9: "LAST_ACK", 10: "LISTEN", 11: "CLOSING"}


# ---- raw HTTP ----

class Reply:
    """What came back on one raw connection: the status (None when no status line came), the
    bytes, whether the server closed (FIN or reset) and how long it took."""

    def __init__(self):
        self.status = None
        self.data = b""
        self.closed = False
        self.reset = False
        self.timed_out = False
        self.elapsed = 0.0
        self.send_error = None

    def __repr__(self):
        return "<status %r, %d bytes%s%s%s, %.2f s: %r>" % (
            self.status, len(self.data), ", closed" if self.closed else "", ", reset" if self.reset else "",
            ", TIMED OUT" if self.timed_out else "", self.elapsed, self.data[:160])


def read_reply(sock, deadline, reply):
    """Reads one response (head and a Content-Length body) or until the server closes."""
    while True:
        head_end = reply.data.find(b"\r\n\r\n")
        if head_end >= 0:
            head = reply.data[:head_end].decode("latin-1")
            first = head.split("\r\n", 1)[0].split()
            if len(first) >= 2 and first[0].startswith("HTTP/") and first[1].isdigit():
                reply.status = int(first[1])
            length = 0
            for line in head.split("\r\n")[1:]:
                name, _, value = line.partition(":")
                if name.strip().lower() == "content-length" and value.strip().isdigit():
                    length = int(value.strip())
            if len(reply.data) >= head_end + 4 + length:
                return reply
        left = deadline - time.time()
        if left <= 0:
            reply.timed_out = True
            return reply
        sock.settimeout(left)
        try:
            chunk = sock.recv(65536)
        except socket.timeout:
            reply.timed_out = True
            return reply
        except (ConnectionResetError, BrokenPipeError):
            reply.closed = reply.reset = True
            return reply
        if not chunk:
            reply.closed = True
            return reply
        reply.data += chunk


def raw(port, data, timeout=8.0, host="127.0.0.1"):
    """Sends `data` as it is and reads what comes back (see Reply)."""
    reply = Reply()
    start = time.time()
    deadline = start + timeout
    sock = socket.create_connection((host, port), timeout=timeout)
    try:
        try:
            sock.sendall(data)
        except socket.timeout:
            reply.send_error = "send timed out"
        except (BrokenPipeError, ConnectionResetError) as e:
            reply.send_error = str(e)  # the server stopped reading: what did it say?
        read_reply(sock, deadline, reply)
    finally:
        sock.close()
    reply.elapsed = time.time() - start
    return reply


def get_line(path):
    return b"GET " + path + b" HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n"


def post_view(body):
    return (b"POST /api/view HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\n"
            b"Content-Length: %d\r\nConnection: close\r\n\r\n" % len(body)) + body


def tcp_state(sock):
    """The kernel's state of our own end of a connection (struct tcp_info's first byte)."""
    return sock.getsockopt(socket.IPPROTO_TCP, socket.TCP_INFO, 8)[0]


def server_side(server_port, client_port):
    """The server's end of the connection from client_port, as /proc/net/tcp lists it: (state, bytes
    not yet acknowledged, socket inode; 0 once the server has closed it), or None when gone."""
    try:
        with open("/proc/net/tcp") as f:
            lines = f.readlines()[1:]
    except OSError:
        return None
    for line in lines:
        cols = line.split()
        local, remote = cols[1], cols[2]
        if int(local.split(":")[1], 16) == server_port and int(remote.split(":")[1], 16) == client_port:
            tx = int(cols[4].split(":")[0], 16)
            return TCP_STATES.get(int(cols[3], 16), cols[3]), tx, int(cols[9])
    return None


def non_loopback_ipv4():
    """An IPv4 address of this machine other than 127.x, or None."""
    try:
        out = subprocess.run(["hostname", "-I"], capture_output=True, text=True, timeout=5).stdout
        for a in out.split():
            if a.count(".") == 3 and not a.startswith("127."):
                return a
    except (OSError, subprocess.SubprocessError):
        pass
    u = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    try:
        u.connect(("10.255.255.255", 1))  # picks the outgoing address; sends nothing
        a = u.getsockname()[0]
        return None if a.startswith("127.") or a == "0.0.0.0" else a
    except OSError:
        return None
    finally:
        u.close()


class HostileClients(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.served = Served(ARGS, LAB)
        cls.s = cls.served.__enter__()
        st = cls.s.wait_state(lambda st: st.get("picture") and not st.get("busy"), 120, "the first picture")
        cls.view = st["view"]
        print("\n[serve] port %d, pid %d, RSS at start %d KiB" % (cls.s.port, cls.s.proc.pid, cls.s.rss_kib()),
              flush=True)

    @classmethod
    def tearDownClass(cls):
        cls.served.__exit__(None, None, None)

    def setUp(self):
        self.assertIsNone(self.s.proc.poll(), "the server exited:\n" + "".join(self.s.output[-30:]))
        self.t0 = time.time()
        self.rss0 = self.s.rss_kib()

    def tearDown(self):
        alive = self.s.proc.poll() is None
        print("\n  [%s] %.1f s; RSS %d -> %s KiB" % (self._testMethodName, time.time() - self.t0, self.rss0,
                                                   self.s.rss_kib() if alive else "(exited)"), flush=True)

    # ---- helpers ----

    def assert_healthy(self, limit=PROMPT_S):
        """The server still answers GET /api/state promptly, with JSON."""
        self.assertIsNone(self.s.proc.poll(), "the server exited:\n" + "".join(self.s.output[-30:]))
        t = time.time()
        try:
            code, body = self.s.get("/api/state", timeout=limit + 10)
        except OSError as e:
            self.fail("GET /api/state failed after %.1f s: %s" % (time.time() - t, e))
        dt = time.time() - t
        self.assertEqual(code, 200)
        state = json.loads(body)
        self.assertIn("version", state)
        self.assertLess(dt, limit, "GET /api/state took %.2f s" % dt)
        return dt

    def assert_refused(self, reply, what, allowed=(400, 404, 405, 413, 414, 431)):
        """Answered with one of `allowed`, or the connection closed; in a few seconds either way."""
        self.assertFalse(reply.timed_out, "%s: neither answered nor closed: %r" % (what, reply))
        if reply.status is None:
            self.assertTrue(reply.closed, "%s: no answer: %r" % (what, reply))
        else:
            self.assertIn(reply.status, allowed, "%s: %r" % (what, reply))

    def poke(self):
        """Bumps the state's version without changing the view: POST /api/view of the view it has."""
        v = self.view
        body = json.dumps({"scene": v["scene"], "yaw": v["yaw"], "pitch": v["pitch"], "zoom": v["zoom"]}).encode()
        req = urllib.request.Request(self.s.url + "api/view", data=body, method="POST",
                                     headers={"Content-Type": "application/json"})
        with urllib.request.urlopen(req, timeout=10) as r:
            self.assertEqual(r.status, 200)

    # ---- 1 ----

    def test_1_traversal_and_absolute_paths(self):
        """No path reaches the file system: traversal, encoded traversal, absolute paths and the
        student's own files are all refused, and nothing of /etc/passwd or of those files comes back."""
        frag = self.s.read("phong.frag")
        with open(os.path.join(ARGS.source, "labs", LAB, "lab.json"), "rb") as f:
            lab_json = f.read()
        secrets = [b"root:", frag.encode()[:60], frag.encode()[-60:], lab_json[:60], lab_json[-60:].strip()]
        secrets = [x for x in secrets if len(x) >= 5]
        paths = [b"/../../../../etc/passwd", b"/assets/../../etc/passwd", b"/%2e%2e/%2e%2e/etc/passwd",
                 b"//etc/passwd", b"/etc/passwd", b"http://127.0.0.1/etc/passwd",
                 b"http://127.0.0.1:%d/etc/passwd" % self.s.port, b"/picture/1/student/../../../../etc/passwd",
                 b"/assets/..%2f..%2fetc%2fpasswd", b"/assets/%2e%2e%2f%2e%2e%2fetc%2fpasswd",
                 b"/..%5c..%5cetc%5cpasswd", b"/..\\..\\etc\\passwd", b"/%2fetc%2fpasswd",
                 b"/picture/1/file/..%2f..%2f..%2fetc%2fpasswd", b"/assets/%00../../etc/passwd",
                 b"/phong.frag", b"/01-phong/phong.frag", b"/./phong.frag", b"/%70hong.frag",
                 b"/labs/01-phong/lab.json", b"/01-phong/lab.json", b"/../labs/01-phong/lab.json",
                 b"/assets/../labs/01-phong/lab.json", b"/assets/../../" + LAB.encode() + b"/phong.frag",
                 b"file:///etc/passwd", b"*"]
        for path in paths:
            for method in (b"GET", b"HEAD"):
                with self.subTest(path=path, method=method):
                    reply = raw(self.s.port, method + get_line(path)[3:])
                    self.assert_refused(reply, (method + b" " + path).decode("latin-1"), allowed=(400, 404, 405))
                    for secret in secrets:
                        self.assertNotIn(secret, reply.data, "%s %s gave a file away: %r" % (method, path, reply))
        # The page itself (compiled in) comes back, and holds none of those files either.
        reply = raw(self.s.port, get_line(b"/"))
        self.assertEqual(reply.status, 200, reply)
        for secret in secrets:
            self.assertNotIn(secret, reply.data)
        self.assert_healthy()

    # ---- 2 ----

    def test_2_huge_header_and_many_fields(self):
        """A 1 MB header line, and 10,000 small header fields: refused or dropped in seconds; the
        server's memory grows by less than 64 MiB and it keeps serving."""
        rss0 = self.s.rss_kib()
        big = (b"GET /api/state HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Big: " + b"a" * 1048576 + b"\r\n\r\n")
        reply = raw(self.s.port, big, timeout=8)
        rss1 = self.s.rss_kib()
        print("\n  1 MB header line: %r; RSS %d -> %d KiB" % (reply, rss0, rss1))
        self.assert_refused(reply, "a 1 MB header line")
        self.assertLess(reply.elapsed, 6.0)
        self.assert_healthy()

        many = (b"GET /api/state HTTP/1.1\r\nHost: 127.0.0.1\r\n" +
                b"".join(b"X-Field-%d: v\r\n" % i for i in range(10000)) + b"\r\n")
        reply = raw(self.s.port, many, timeout=8)
        rss2 = self.s.rss_kib()
        print("  10,000 header fields (%d bytes): %r; RSS %d -> %d KiB" % (len(many), reply, rss1, rss2))
        self.assert_refused(reply, "10,000 header fields")
        self.assertLess(reply.elapsed, 6.0)

        # Several at once, so that memory held per connection would show.
        results = []

        def one(data):
            results.append(raw(self.s.port, data, timeout=10))

        threads = [threading.Thread(target=one, args=(big if i % 2 else many,)) for i in range(8)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        rss3 = self.s.rss_kib()
        print("  8 at once: statuses %s; RSS %d -> %d KiB" % ([r.status for r in results], rss2, rss3))
        for r in results:
            self.assert_refused(r, "a huge header (8 at once)")
        self.assertLess(max(rss1, rss2, rss3) - rss0, 64 * 1024, "RSS grew by more than 64 MiB")
        self.assert_healthy()

    # ---- 3 ----

    def test_3_ten_thousand_idle_connections(self):
        """10,000 connections opened and left idle: a normal request is still answered within 15 s,
        memory stays bounded, and once they are gone the server serves as before."""
        want = 10000
        soft, hard = resource.getrlimit(resource.RLIMIT_NOFILE)
        need = want + 256
        if soft < need:
            try:
                resource.setrlimit(resource.RLIMIT_NOFILE, (max(need, soft), max(need, hard)))
            except (ValueError, OSError):
                resource.setrlimit(resource.RLIMIT_NOFILE, (hard, hard))
        soft = resource.getrlimit(resource.RLIMIT_NOFILE)[0]
        n = min(want, soft - 256)
        if n < want:
            print("\n  RLIMIT_NOFILE allows only %d connections" % n)
        if n < 1000:
            self.skipTest("RLIMIT_NOFILE (%d) leaves too few descriptors and cannot be raised" % soft)

        rss0 = self.s.rss_kib()
        socks = []
        sel = selectors.DefaultSelector()
        try:
            start = time.time()
            refused = 0
            for _ in range(n):
                c = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
                c.setblocking(False)
                err = c.connect_ex(("127.0.0.1", self.s.port))
                if err not in (0, errno.EINPROGRESS):
                    refused += 1
                    c.close()
                    continue
                socks.append(c)
                sel.register(c, selectors.EVENT_WRITE)
            pending = len(socks)
            completed, failed = [], 0
            while pending and time.time() - start < 10.0:
                for key, _ in sel.select(0.2):
                    c = key.fileobj
                    sel.unregister(c)
                    pending -= 1
                    if c.getsockopt(socket.SOL_SOCKET, socket.SO_ERROR) == 0:
                        completed.append(c)
                    else:
                        failed += 1
            print("\n  %d connects: %d completed in %.1f s, %d failed, %d still pending, %d refused at once" %
                  (n, len(completed), time.time() - start, failed, pending, refused))
            self.assertGreater(len(completed), 256, "too few connections completed to load the server")

            # While they are held (idle): normal requests, timed.
            latencies = []
            for _ in range(3):
                t = time.time()
                try:
                    code, body = self.s.get("/api/state", timeout=15)
                except OSError as e:
                    self.fail("GET /api/state under %d idle connections failed after %.1f s: %s" %
                              (len(completed), time.time() - t, e))
                latencies.append(time.time() - t)
                self.assertEqual(code, 200)
                json.loads(body)
                time.sleep(1.0)
            rss1 = self.s.rss_kib()
            threads = len(os.listdir("/proc/%d/task" % self.s.proc.pid))
            print("  GET /api/state under them: %s s; RSS %d -> %d KiB; server threads %d" %
                  (", ".join("%.3f" % x for x in latencies), rss0, rss1, threads))
            self.assertLess(max(latencies), 15.0)
            self.assertLess(rss1 - rss0, 200 * 1024, "RSS grew by more than 200 MiB")

            # Which of them did the server shed (FIN or reset seen on our side)?
            dropped = 0
            for c in completed:
                try:
                    if c.recv(1) == b"":
                        dropped += 1
                except BlockingIOError:
                    pass
                except OSError:
                    dropped += 1
            print("  dropped by the server after %.1f s: %d of %d (the rest wait in the kernel's queues)" %
                  (time.time() - start, dropped, len(completed)))
            self.assertGreater(dropped, 0, "the guard shed none of the idle connections it accepted")
        finally:
            sel.close()
            for c in socks:
                c.close()
        t = time.time()
        dt = self.assert_healthy()
        rss2 = self.s.rss_kib()
        print("  after closing them: GET /api/state in %.3f s; RSS %d KiB" % (dt, rss2))
        for _ in range(5):
            self.assertLess(self.assert_healthy(limit=2.0), 2.0)

    # ---- 4 ----

    def test_4_slow_reader(self):
        """Clients that ask for a picture and read it one byte a second, one keeping the connection
        alive and one asking to close it: others are answered promptly meanwhile, and within 30 s
        the server lets each go: its end of the connection is gone (or ours sees EOF or a reset), so
        that nothing of the server's, not even a closed socket's buffers in its kernel, waits on the
        reader. (Closing the socket is not enough: the kernel goes on handing the rest out at the
        reader's pace, for minutes.)"""
        st = self.s.wait_state(lambda st: st.get("picture") and st["picture"].get("final_image", -1) >= 0,
                               60, "a picture")
        pic = st["picture"]
        path = "/picture/%d/student/%d.png" % (pic["seq"], pic["final_image"])
        code, png = self.s.get(path)
        self.assertEqual(code, 200)
        self.assertGreater(len(png), 16 * 1024, "the picture is too small to fill the buffers")

        class Reader:
            def __init__(self, name, close):
                self.name, self.got, self.how, self.at, self.fd_closed_at = name, 0, None, None, None
                self.sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
                self.sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 1024)  # before connect
                self.close = close

        readers = [Reader("keep-alive", False), Reader("Connection: close", True)]
        try:
            for r in readers:
                r.sock.connect(("127.0.0.1", self.s.port))
                r.port = r.sock.getsockname()[1]
                r.sock.sendall(("GET %s HTTP/1.1\r\nHost: 127.0.0.1\r\n%s\r\n" %
                                (path, "Connection: close\r\n" if r.close else "")).encode())
                r.sock.settimeout(0.2)
            start = time.time()
            worst_other = 0.0
            next_other = start + 2.0
            while time.time() - start < 30.0 and any(r.how is None for r in readers):
                tick = time.time()
                for r in readers:
                    if r.how is not None:
                        continue
                    try:
                        b = r.sock.recv(1)
                        if b == b"":
                            r.how = "EOF on our end"
                        r.got += len(b)
                    except socket.timeout:
                        pass
                    except (ConnectionResetError, BrokenPipeError):
                        r.how = "reset on our end"
                    state = tcp_state(r.sock)
                    if r.how is None and state != 1:
                        r.how = "our end went %s (SO_ERROR %d)" % (
                            TCP_STATES.get(state), r.sock.getsockopt(socket.SOL_SOCKET, socket.SO_ERROR))
                    side = server_side(self.s.port, r.port)
                    if r.fd_closed_at is None and (side is None or side[2] == 0):
                        r.fd_closed_at = time.time() - start
                    if r.how is None and (side is None or side[0] in ("TIME_WAIT", "CLOSE")):
                        r.how = "the server's end is gone" if side is None else "the server's end is " + side[0]
                    if r.how is not None:
                        r.at = time.time() - start
                if time.time() >= next_other:
                    t = time.time()
                    code, _ = self.s.get("/api/state", timeout=10)
                    self.assertEqual(code, 200)
                    worst_other = max(worst_other, time.time() - t)
                    next_other = time.time() + 3.0
                time.sleep(max(0.0, 1.0 - (time.time() - tick)))
            print()
            for r in readers:
                print("  slow reader (%s): read %d of %d+ bytes; %s after %s; the server closed its socket "
                      "at %s; its end now: %s" %
                      (r.name, r.got, len(png), r.how or "NOT let go",
                       "%.1f s" % r.at if r.at is not None else "%.1f s" % (time.time() - start),
                       "%.1f s" % r.fd_closed_at if r.fd_closed_at is not None else "(never)",
                       server_side(self.s.port, r.port)))
            print("  other requests meanwhile: worst %.3f s" % worst_other)
            self.assertLess(worst_other, PROMPT_S, "others were kept waiting by the slow readers")
            for r in readers:
                self.assertLess(r.got, len(png), "%s: the whole picture fitted in the buffers" % r.name)
                side = server_side(self.s.port, r.port)
                self.assertIsNotNone(
                    r.how, "slow reader (%s) not let go within 30 s: our end is still ESTABLISHED and the "
                    "server's end is %s (state, bytes not taken, inode; inode 0: the server closed its socket, "
                    "at %s s, but its kernel still holds the rest and hands it out at the reader's pace)" %
                    (r.name, side, "%.1f" % r.fd_closed_at if r.fd_closed_at is not None else "?"))
        finally:
            for r in readers:
                r.sock.close()  # unread data: a reset, which frees whatever the server's kernel holds
        self.assert_healthy()

    # ---- 5 ----

    def test_5_slowloris(self):
        """Clients that send their headers a byte at a time. The guard shuts a connection down once
        it is 60 s old (GuardLimits::max_age_s), however busily it trickles: one trickling a byte
        every 0.25 s (so the idle rule never applies) must be dropped within 70 s. Meanwhile, while
        50 more trickle a byte a second for 10 s, other requests are answered promptly."""
        lock = threading.Lock()
        stop_crowd = threading.Event()
        stop_all = threading.Event()
        start = time.time()
        age = socket.create_connection(("127.0.0.1", self.s.port), timeout=5)
        age.sendall(b"GET /api/state HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Slow: ")
        age.setblocking(False)
        crowd = []
        result = {"age_dropped": None, "age_how": None, "crowd_dropped": 0, "age_bytes": 0}

        def age_dropped(how):
            result["age_dropped"] = time.time() - start
            result["age_how"] = how

        def trickle():
            n = 0
            dead = set()
            while not stop_all.is_set() and result["age_dropped"] is None:
                n += 1
                # the measured one: a byte every 0.25 s, after looking whether the server let go
                try:
                    try:
                        data = age.recv(4096)
                        age_dropped("EOF" if data == b"" else "answered %r" % data[:40])
                        break
                    except BlockingIOError:
                        pass
                    age.send(b"a")
                    result["age_bytes"] += 1
                except OSError as e:
                    age_dropped("error %s" % e)
                    break
                # the crowd: a byte a second each
                if n % 4 == 0 and not stop_crowd.is_set():
                    with lock:
                        members = list(enumerate(crowd))
                    for i, c in members:
                        if i in dead:
                            continue
                        try:
                            c.send(b"a")
                        except BlockingIOError:
                            pass
                        except OSError:
                            dead.add(i)
                            result["crowd_dropped"] += 1
                stop_all.wait(0.25)

        th = threading.Thread(target=trickle, daemon=True)
        th.start()
        try:
            for _ in range(50):
                c = socket.create_connection(("127.0.0.1", self.s.port), timeout=10)
                c.sendall(b"GET /api/state HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Slow: ")
                c.setblocking(False)
                with lock:
                    crowd.append(c)
            opened = time.time() - start
            latencies = []
            while time.time() - start < opened + 10.0:
                t = time.time()
                code, body = self.s.get("/api/state", timeout=15)
                latencies.append(time.time() - t)
                self.assertEqual(code, 200)
                json.loads(body)
                time.sleep(0.5)
            stop_crowd.set()
            print("\n  50 slowloris clients (opened in %.1f s), then 10 s: %d requests meanwhile, worst %.3f s; "
                  "%d of the 50 dropped" % (opened, len(latencies), max(latencies), result["crowd_dropped"]))
            self.assertLess(max(latencies), PROMPT_S, "the slowloris clients kept others waiting")
            with lock:
                for c in crowd:
                    c.close()
            th.join(75.0 - (time.time() - start))
        finally:
            stop_all.set()
            th.join(5)
            age.close()
            with lock:
                for c in crowd:
                    c.close()
        print("  the one trickling 4 bytes a second: %s after %s s (%d bytes sent)" %
              (result["age_how"] or "NOT dropped",
               "%.1f" % result["age_dropped"] if result["age_dropped"] else "%.1f" % (time.time() - start),
               result["age_bytes"]))
        self.assertIsNotNone(result["age_dropped"], "a slowloris client was not dropped within 75 s")
        self.assertLess(result["age_dropped"], 70.0)
        self.assert_healthy()

    # ---- 6 ----

    def test_6_malformed_requests(self):
        """Garbage, a request line without a version, a 100 KB URI, a 1 MB body, bad JSON and an unknown
        scene: each answered 4xx or closed, in seconds; the view is unchanged and the server serves on."""
        port = self.s.port
        cases = [
            ("garbage bytes", bytes(range(256)) * 4 + b"\r\n\r\n"),
            ("binary without line ends", os.urandom(2048)),
            ("a request line without version", b"GET /api/state\r\n\r\n"),
            ("a request line of one word", b"GET\r\n\r\n"),
            ("an unknown version", b"GET /api/state HTTP/9.9\r\nHost: x\r\n\r\n"),
            ("a 100 KB URI", b"GET /" + b"a" * 100000 + b" HTTP/1.1\r\nHost: x\r\n\r\n"),
            ("a 100 KB query", b"GET /api/state?" + b"a=1&" * 25000 + b" HTTP/1.1\r\nHost: x\r\n\r\n"),
            ("a header line without a colon", b"GET /nope HTTP/1.1\r\nHost: x\r\nNo colon here\r\n\r\n"),
            ("POST /api/view with a 1 MB body",
             b"POST /api/view HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\nContent-Length: 1048576"
             b"\r\n\r\n" + b"[" * 1048576),
            ("POST /api/view with a 1 MB chunked body",
             b"POST /api/view HTTP/1.1\r\nHost: x\r\nTransfer-Encoding: chunked\r\n\r\n100000\r\n" +
             b"[" * 1048576 + b"\r\n0\r\n\r\n"),
            ("POST /api/view with a huge Content-Length",
             b"POST /api/view HTTP/1.1\r\nHost: x\r\nContent-Length: 99999999999999999999999\r\n\r\n{}"),
            ("POST /api/view with a negative Content-Length",
             b"POST /api/view HTTP/1.1\r\nHost: x\r\nContent-Length: -5\r\n\r\n{}"),
            ("POST /api/view with invalid JSON", post_view(b'{"scene": nope')),
            ("POST /api/view with JSON that is not an object", post_view(b"[1, 2, 3]")),
            ("POST /api/view with a wrongly typed field", post_view(b'{"scene": "sphere", "yaw": "x"}')),
            ("POST /api/view with a non-existent scene", post_view(b'{"scene": "no_such_scene_at_all"}')),
            ("POST /api/view with a scene that is a path", post_view(b'{"scene": "../../../../etc/passwd"}')),
            ("POST /api/view with an empty body", post_view(b"")),
            ("POST /api/view with an unknown debug view", post_view(b'{"scene": "sphere", "debug": "positions"}')),
            ("POST /api/view with a debug view that is a path",
             post_view(b'{"scene": "sphere", "debug": "../../../../etc/passwd"}')),
            ("POST /api/view with a debug view that is a number", post_view(b'{"scene": "sphere", "debug": 3}')),
            ("GET /api/view", get_line(b"/api/view")),
            ("an unknown method", b"BREW /api/state HTTP/1.1\r\nHost: x\r\n\r\n"),
        ]
        before = self.s.state()["view"]
        # All at once (each on its own connection): a bogus Content-Length is only refused once the
        # read times out (5 s), so one at a time would take long.
        replies = {}

        def one(what, data):
            try:
                replies[what] = raw(port, data, timeout=10)
            except OSError as e:
                replies[what] = e

        threads = [threading.Thread(target=one, args=case) for case in cases]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        print()
        for what, _ in cases:
            reply = replies[what]
            print("  %s: %r" % (what, reply))
            with self.subTest(what=what):
                self.assertIsInstance(reply, Reply)
                self.assert_refused(reply, what, allowed=(400, 404, 405, 411, 413, 414, 431, 501, 505))
                self.assertLess(reply.elapsed, 8.0, what)
                self.assertNotIn(b"root:", reply.data)
        after = self.s.state()["view"]
        self.assertEqual(before, after, "a refused request changed the view")
        self.assert_healthy()

    # ---- 7 ----

    def open_stream(self, timeout=5.0):
        c = socket.create_connection(("127.0.0.1", self.s.port), timeout=timeout)
        c.sendall(b"GET /events HTTP/1.1\r\nHost: 127.0.0.1\r\nAccept: text/event-stream\r\n\r\n")
        reply = Reply()
        deadline = time.time() + timeout
        while b"\r\n\r\n" not in reply.data and time.time() < deadline:
            c.settimeout(max(0.01, deadline - time.time()))
            try:
                chunk = c.recv(4096)
            except socket.timeout:
                break
            except OSError:
                reply.closed = True
                break
            if not chunk:
                reply.closed = True
                break
            reply.data += chunk
        first = reply.data.split(b"\r\n", 1)[0].split()
        if len(first) >= 2 and first[1].isdigit():
            reply.status = int(first[1])
        return c, reply

    def test_7_event_streams_limit(self):
        """Sixteen pages may listen to /events at once; the seventeenth gets 503; closing one frees
        its slot."""
        streams = []
        try:
            for i in range(16):
                c, reply = self.open_stream()
                streams.append(c)
                self.assertEqual(reply.status, 200, "stream %d: %r" % (i + 1, reply))
                self.assertIn(b"text/event-stream", reply.data)
            c, reply = self.open_stream()
            c.close()
            self.assertEqual(reply.status, 503, "the 17th stream: %r" % reply)
            self.assert_healthy()  # the streams hold no request back

            streams.pop(0).close()
            # A stream notices its page went away when it next writes: at the next change, or the
            # next keep-alive comment (15 s). A change now makes it write.
            closed = time.time()
            self.poke()
            freed = None
            while time.time() - closed < 20.0:
                c, reply = self.open_stream()
                if reply.status == 200:
                    streams.append(c)
                    freed = time.time() - closed
                    break
                c.close()
                self.assertEqual(reply.status, 503, reply)
                time.sleep(0.25)
            print("\n  a closed stream's slot was free again after %s" %
                  ("%.2f s" % freed if freed is not None else "(never, within 20 s)"))
            self.assertIsNotNone(freed, "closing a stream did not free its slot within 20 s")
        finally:
            for c in streams:
                c.close()
            self.poke()  # so that the streams notice they are closed
        # All slots come back.
        deadline = time.time() + 20.0
        while True:
            c, reply = self.open_stream()
            c.close()
            if reply.status == 200 or time.time() > deadline:
                break
            time.sleep(0.25)
        self.assertEqual(reply.status, 200, "the slots did not come back after all streams closed")
        self.poke()
        self.assert_healthy()

    # ---- 8 ----

    def test_8_binds_loopback_by_default(self):
        """By default it says http://127.0.0.1:PORT/ and cannot be reached on the machine's other
        addresses; --host 0.0.0.0 prints a WARNING (and is then reachable there)."""
        out = "".join(self.s.output)
        self.assertIn("http://127.0.0.1:%d/" % self.s.port, out)
        self.assertNotIn("WARNING", out)
        addr = non_loopback_ipv4()
        if addr is None:
            print("\n  no non-loopback IPv4 address here: reachability not checked")
        else:
            try:
                c = socket.create_connection((addr, self.s.port), timeout=3)
            except OSError as e:
                print("\n  %s:%d refused as it should be: %s" % (addr, self.s.port, e))
            else:
                c.close()
                self.fail("the default server is reachable on %s:%d" % (addr, self.s.port))
        with Served(ARGS, LAB, extra=["--host", "0.0.0.0"]) as wide:
            text = "".join(wide.output)
            warnings = [line for line in wide.output if "WARNING" in line]
            print("  --host 0.0.0.0 says: %s" % (warnings[0].strip() if warnings else "(no warning)"))
            self.assertTrue(warnings, "no WARNING for --host 0.0.0.0:\n" + text)
            self.assertIn("0.0.0.0", warnings[0])
            self.assertEqual(wide.get("/api/state")[0], 200)
            if addr is not None:  # the control: that address does reach a server bound to it
                try:
                    reply = raw(wide.port, get_line(b"/api/state"), host=addr, timeout=5)
                    print("  control: the 0.0.0.0 server answers on %s: %r" % (addr, reply.status))
                except OSError as e:
                    print("  control: the 0.0.0.0 server is not reachable on %s either (%s): the refusal above "
                          "shows little here" % (addr, e))
        self.assert_healthy()

    # ---- 9 ----

    def test_9_port_in_use(self):
        """A second `shaderlab serve` on a port this one listens on fails, saying so (exit 2), rather
        than sharing it: requests to the port would otherwise go to either program at random."""
        cmd = [ARGS.shaderlab, "serve", LAB, "--submission", self.s.root, "--port", str(self.s.port),
               "--labs", os.path.join(ARGS.source, "labs")]
        second = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        try:
            out, _ = second.communicate(timeout=8)
            rc = second.returncode
        except subprocess.TimeoutExpired:
            second.send_signal(2)  # SIGINT: it stops as it would on Ctrl-C
            try:
                out, _ = second.communicate(timeout=20)
            except subprocess.TimeoutExpired:
                second.kill()
                out, _ = second.communicate()
            rc = None
        print("\n  a second serve on port %d: exit %s: %s" % (self.s.port, rc, out.strip().replace("\n", " | ")))
        self.assertIsNotNone(rc, "a second serve on port %d started and served beside the first (SO_REUSEPORT?): "
                             "%s" % (self.s.port, out.strip()))
        self.assertEqual(rc, 2, out)
        self.assertIn("cannot listen", out)
        self.assert_healthy()


def main():
    global ARGS
    ARGS = serve_fixture.parse_args()
    ARGS.shaderlab = os.path.abspath(ARGS.shaderlab)
    ARGS.source = os.path.abspath(ARGS.source)
    if not os.path.exists(ARGS.shaderlab):
        print("skipped: %s does not exist (build it first)" % ARGS.shaderlab)
        return SKIP
    if not sys.platform.startswith("linux"):
        print("skipped: these tests read Linux's TCP_INFO and /proc")
        return SKIP
    start = time.time()
    argv = [sys.argv[0]] + list(ARGS.tests)
    prog = unittest.main(argv=argv, verbosity=2, exit=False)
    print("serve_hostile: %.1f s in all" % (time.time() - start))
    return 0 if prog.result.wasSuccessful() else 1


if __name__ == "__main__":
    sys.exit(main())
