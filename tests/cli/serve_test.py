#!/usr/bin/env python3
"""fvrml-run --serve without a browser: the page, its scripts and the scene's glTF are served; an edit
of the scene (or of a file it Inlines) reaches the event stream within 2 s; a broken save keeps the
last good glTF and sends the diagnostics, a fixed one clears them; nothing outside the served paths
can be read; bounded requests; Ctrl-C ends it cleanly.
usage: serve_test.py FVRML_RUN SOURCE_DIR"""
import http.client
import json
import os
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time
import urllib.parse

RUN, SRC = sys.argv[1], sys.argv[2]
fails = 0
checks = 0


def check(name, ok, detail=""):
    global fails, checks
    checks += 1
    if not ok:
        fails += 1
        print(f"FAIL {name} {detail}")


BALL = '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "RADIUS^2 - x^2 - y^2 - z^2" bboxSize 2 2 2 resolution [20] } }\nInline { url "part.wrl" }\n'
PART = '#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "0.2^2 - (x-0.8)^2 - y^2 - z^2" bboxSize 2 2 2 resolution [12] } }\n'


started = []  # every server, killed at the end whatever happened


class Server:
    def __init__(self, scene, *args, env=None):
        self.proc = subprocess.Popen([RUN, scene, "--serve", "--port", "0", *args], stdout=subprocess.PIPE,
                                     stderr=subprocess.PIPE, text=True, env=env)
        started.append(self.proc)
        line = self.proc.stdout.readline()
        self.url = line.split(" at ")[1].split(" ")[0] if " at " in line else ""
        parsed = urllib.parse.urlparse(self.url)
        self.host, self.port = parsed.hostname, parsed.port

    def request(self, method, path, body=None):
        c = http.client.HTTPConnection(self.host, self.port, timeout=10)
        c.putrequest(method, path, skip_accept_encoding=True)  # the path as written: no normalising
        if body is not None:
            c.putheader("Content-Length", str(len(body)))
        c.endheaders(body)
        r = c.getresponse()
        data = r.read()
        c.close()
        return r.status, data

    def state(self):
        status, data = self.request("GET", "/state.json")
        return json.loads(data) if status == 200 else {}

    def wait_state(self, pred, seconds):
        end = time.time() + seconds
        while time.time() < end:
            s = self.state()
            if s and pred(s):
                return s
            time.sleep(0.05)
        return self.state()

    def stop(self):
        self.proc.send_signal(signal.SIGINT)
        try:
            out, err = self.proc.communicate(timeout=10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            return None, "", "did not stop"
        return self.proc.returncode, out, err


class Events(threading.Thread):
    """Reads the Server-Sent Events stream, keeping each state event's data."""

    def __init__(self, server):
        super().__init__(daemon=True)
        self.conn = http.client.HTTPConnection(server.host, server.port, timeout=30)
        self.conn.request("GET", "/events")
        self.response = self.conn.getresponse()
        self.states, self.progress = [], []

    def run(self):
        event = None
        try:
            for raw in self.response:
                line = raw.decode().rstrip("\n")
                if line.startswith("event: "):
                    event = line[7:]
                elif line.startswith("data: ") and event == "state":
                    self.states.append(json.loads(line[6:]))
                elif line.startswith("data: ") and event == "progress":
                    self.progress.append(json.loads(line[6:]))
        except Exception:
            pass

    def wait(self, pred, seconds):
        end = time.time() + seconds
        while time.time() < end:
            for s in list(self.states):
                if pred(s):
                    return s
            time.sleep(0.05)
        return None


def write(path, text):
    with open(path + ".tmp", "w") as f:  # as editors save: a new file renamed over the old
        f.write(text)
    os.replace(path + ".tmp", path)


def main(d):
    scene, part = os.path.join(d, "scene.wrl"), os.path.join(d, "part.wrl")
    write(scene, BALL.replace("RADIUS", "0.5"))
    write(part, PART)
    os.symlink("/etc/passwd", os.path.join(d, "passwd"))
    s = Server(scene)
    check("--serve prints its URL", s.url.startswith("http://127.0.0.1:"), repr(s.url))
    status, page = s.request("GET", "/")
    check("the page", status == 200 and b'<script src="/preview.js">' in page and b'<script src="/viewer.js">' in page, str(status))
    status, js = s.request("GET", "/preview.js")
    check("the page's script", status == 200 and b"new EventSource('/events?page=' + pageId)" in js and b"sendBeacon('/closed?page='" in js, str(status))
    status, js = s.request("GET", "/viewer.js")
    check("the view shared with the browser page (web/viewer.js)", status == 200 and b"function FvrmlViewer(" in js, str(status))
    for path in ["/three/three.min.js", "/three/examples/js/loaders/GLTFLoader.js",
                 "/three/examples/js/controls/OrbitControls.js"]:
        status, _ = s.request("GET", path)
        check("three.js from libjs-three: " + path, status == 200, str(status))
    first = s.wait_state(lambda st: st.get("version", 0) >= 1, 30)
    check("the first run is good", first.get("ok") is True, json.dumps(first)[:300])
    check("its stats: backend and resolution", (first.get("stats") or {}).get("backend") == "auto" and first.get("scale") == 1)
    status, glb1 = s.request("GET", "/scene.glb")
    check("the scene as glTF", status == 200 and glb1[:4] == b"glTF", str(status))
    events = Events(s)
    events.start()
    check("the event stream starts with the state", events.wait(lambda st: st["version"] == first["version"], 5) is not None)

    # An edit reaches the stream within 2 s, and the glTF changes.
    t0 = time.time()
    write(scene, BALL.replace("RADIUS", "0.7"))
    edited = events.wait(lambda st: st["version"] > first["version"], 2.0)
    check("an edit reaches the page within 2 s", edited is not None and edited["ok"], f"{time.time() - t0:.2f} s")
    status, glb2 = s.request("GET", "/scene.glb")
    check("the edited scene's glTF", status == 200 and glb2[:4] == b"glTF" and glb2 != glb1)
    v = s.state()["version"]
    write(part, PART.replace("0.2^2", "0.3^2"))
    inlined = events.wait(lambda st: st["version"] > v, 2.0)
    check("an edit of an Inlined file reaches the page within 2 s", inlined is not None and inlined["ok"])
    status, glb3 = s.request("GET", "/scene.glb")

    # A broken save: the diagnostics, and the last good scene stays.
    v = s.state()["version"]
    write(scene, BALL.replace("RADIUS", "0.7 +"))
    broken = events.wait(lambda st: st["version"] > v, 2.0)
    check("a broken save sends its diagnostics", broken is not None and not broken["ok"] and
          "scene.wrl:2:" in broken["diagnostics"] and "error:" in broken["diagnostics"] and "^" in broken["diagnostics"],
          json.dumps(broken)[:400])
    status, kept = s.request("GET", "/scene.glb")
    check("the last good glTF stays", status == 200 and kept == glb3)
    v = s.state()["version"]
    write(scene, BALL.replace("RADIUS", "0.6"))
    fixed = events.wait(lambda st: st["version"] > v, 2.0)
    check("a fixed save clears the diagnostics", fixed is not None and fixed["ok"] and "error" not in fixed["diagnostics"])

    # A missing Inline: a good run (the scene without it) whose diagnostics carry the warning.
    v = s.state()["version"]
    write(scene, BALL.replace("RADIUS", "0.6") + '\nInline { url "nothere.wrl" }\n')
    warned = events.wait(lambda st: st["version"] > v, 2.0)
    check("a missing Inline: the scene without it, and the warning", warned is not None and warned["ok"] and
          "warning: Inline 'nothere.wrl': cannot read" in warned["diagnostics"] and
          (warned.get("stats") or {}).get("missing_inlines", [{}])[0].get("url") == "nothere.wrl", json.dumps(warned)[:400])
    status, glb4 = s.request("GET", "/scene.glb")
    check("a missing Inline: the scene's glTF", status == 200 and glb4[:4] == b"glTF")
    # A shape diagnostic: the ball is cut by its box; the page's overlay gets it, the stats too.
    v = s.state()["version"]
    write(scene, BALL.replace("RADIUS", "1.1"))
    cut = events.wait(lambda st: st["version"] > v, 2.0)
    check("a shape diagnostic in the diagnostics and the stats", cut is not None and cut["ok"] and
          "scene.wrl:2:" in cut["diagnostics"] and "warning: the box cuts the shape" in cut["diagnostics"] and
          "cut" in [d["issue"] for d in (cut.get("stats") or {}).get("shape_diagnostics", [])], json.dumps(cut)[:400])
    v = s.state()["version"]
    write(scene, BALL.replace("RADIUS", "0.6"))
    events.wait(lambda st: st["version"] > v, 2.0)

    # Four open pages at most; one that says it closed frees its slot at once (a reload got 503).
    def open_stream(page):
        sock = socket.create_connection((s.host, s.port), timeout=10)
        sock.sendall(f"GET /events?page={page} HTTP/1.1\r\nHost: x\r\n\r\n".encode())
        return sock, sock.recv(64).decode(errors="replace").split("\r\n")[0]
    streams = [open_stream(f"p{k}") for k in range(3)]  # the fourth is this test's own (Events)
    check("four pages get their streams", all(" 200 " in line for _, line in streams), str([l for _, l in streams]))
    extra, line = open_stream("p4")
    check("a fifth page gets 503", " 503 " in line, line)
    extra.close()
    t0 = time.time()
    status, _ = s.request("POST", "/closed?page=p0", b"")
    again, line = open_stream("p5")
    check("a page that closed frees its slot at once", status == 204 and " 200 " in line and time.time() - t0 < 2,
          f"{status} {line} {time.time() - t0:.2f} s")
    for sock, _ in streams + [(again, "")]:
        sock.close()

    # The resolution scale from the page.
    status, _ = s.request("POST", "/settings?scale=0.5", b"")
    check("settings: a resolution scale", status == 200, str(status))
    scaled = events.wait(lambda st: st.get("scale") == 0.5 and st["ok"], 5)
    check("the scene runs again at that scale", scaled is not None and scaled["stats"]["resolution_scale"] == 0.5)
    status, _ = s.request("POST", "/settings?scale=100", b"")
    check("settings: a scale out of range", status == 400, str(status))
    status, _ = s.request("POST", "/settings?scale=1", b"x" * 200000)
    check("a request body over the bound", status == 413, str(status))

    # Nothing else can be read.
    for path in ["/../etc/passwd", "/%2e%2e/%2e%2e/etc/passwd", "/three/../../../../etc/passwd",
                 "/three/build/..%2f..%2f..%2f..%2fetc%2fpasswd", "//etc/passwd", "/etc/passwd", "/passwd",
                 "/scene.wrl", "/part.wrl", "/" + scene, "/three/three.min.jsx", "/scene.glb/../state.json"]:
        status, data = s.request("GET", path)
        check("404 for " + path, status == 404 and b"root:" not in data, f"{status} {data[:60]!r}")

    code, out, err = s.stop()
    check("Ctrl-C ends it cleanly", code == 0 and "stopped" in out, f"{code} {out!r} {err[-300:]!r}")
    check("a broken save's errors on the terminal too", "scene.wrl:2:" in err and "error:" in err, err[-500:])
    check("and the word when it is good again", "scene.wrl: no errors now" in err, err[-500:])
    check("a missing Inline's warning on the terminal too", "warning: Inline 'nothere.wrl'" in err, err[-500:])
    check("the scratch folder is gone", not any(n.startswith(f"fvrml-serve-{s.proc.pid}-")
                                                for n in os.listdir(tempfile.gettempdir())))

    # A longer run sends its progress while it goes; every example of the repository previews.
    big = os.path.join(d, "gyroid.wrl")
    write(big, open(os.path.join(SRC, "bench/scenes/gyroid-sphere256.wrl")).read())
    s = Server(big, "--frames", "4")  # about a second per run (slower under sanitizers): progress meanwhile
    first = s.wait_state(lambda st: st.get("version", 0) >= 1 and st.get("partial") is None, 120)
    events = Events(s)
    events.start()
    events.wait(lambda st: st["version"] == first["version"], 5)
    write(big, open(big).read().replace("0.9^2", "0.89^2"))  # a change the memo of meshes cannot skip
    done = events.wait(lambda st: st["version"] > first["version"] and st["partial"] is None, 120)
    check("a run sends its progress", done is not None and len(events.progress) > 0 and
          all(0 <= p["fraction"] <= 1 and p["what"] for p in events.progress), str(events.progress[:3]))
    s.stop()
    examples = [os.path.join(SRC, "examples/paper", f) for f in sorted(os.listdir(os.path.join(SRC, "examples/paper")))]
    examples += [os.path.join(SRC, "examples", f) for f in sorted(os.listdir(os.path.join(SRC, "examples"))) if f.endswith(".fs")]
    for example in examples:  # two frames at half resolution: the same path, quick even under sanitizers
        s = Server(example, "--frames", "2", "--resolution-scale", "0.5")
        st = s.wait_state(lambda st: st.get("version", 0) >= 1 and st.get("partial") is None, 120)
        status, glb = s.request("GET", "/scene.glb")
        check("previews " + os.path.relpath(example, SRC), st.get("ok") is True and status == 200 and glb[:4] == b"glTF",
              (st.get("diagnostics") or "")[:200])
        s.stop()

    # --open asks the desktop (xdg-open) to show the page: a stand-in on PATH records what it was given.
    opener = os.path.join(d, "bin")
    os.makedirs(opener)
    with open(os.path.join(opener, "xdg-open"), "w") as f:
        f.write(f'#!/bin/sh\necho "$1" > {d}/opened\n')
    os.chmod(os.path.join(opener, "xdg-open"), 0o755)
    s = Server(scene, "--open", env=dict(os.environ, PATH=opener + os.pathsep + os.environ["PATH"]))
    end = time.time() + 30  # a shell started beside the server: seconds on a loaded machine
    while time.time() < end and not os.path.exists(os.path.join(d, "opened")):
        time.sleep(0.05)
    opened = open(os.path.join(d, "opened")).read().strip() if os.path.exists(os.path.join(d, "opened")) else ""
    check("--open: xdg-open gets the page's URL", opened == s.url, f"{opened!r} {s.url!r}")
    s.stop()
    s = Server(scene, "--open", env=dict(os.environ, PATH=d))  # no xdg-open: a note, and it serves on
    code, out, err = s.stop()
    check("--open without xdg-open: a note, still serving", code == 0 and "open " + s.url in err, err[-200:])

    # A run is cancelled within a batch of evaluations (a fraction of a second here), not at the end
    # of a frame: this scene's one frame takes minutes. Over --max-seconds: an error on the page.
    slow = os.path.join(d, "slow.wrl")
    slow_text = ('#VRML V2.0 utf8\nFShape { geometry FGeometry { definition "function FRep(x, y, z, t) { '
                 'var s = 0; for (var i = 0; i < 10000; i++) s += sin(x * i + t); return 0.5 - x * x - y * y - '
                 'z * z + 1e-9 * s; }" bboxSize 2 2 2 resolution [160] } }\n')
    write(slow, slow_text)
    s = Server(slow, "--max-seconds", "1", "--backend", "vm")
    st = s.wait_state(lambda st: "took longer" in st.get("diagnostics", ""), 60)
    check("--serve --max-seconds: the run is stopped with an error on the page",
          st.get("ok") is False and "error: the run took longer than 1 s (--max-seconds 1); stopped" in st.get("diagnostics", ""),
          str(st)[:300])
    check("--serve --max-seconds: the server goes on", s.request("GET", "/")[0] == 200)
    code, out, err = s.stop()
    check("--serve --max-seconds: Ctrl-C ends it cleanly", code == 0, f"{code} {err[-300:]!r}")
    # A save during that frame cancels it and runs the new scene; Ctrl-C during it ends the server.
    s = Server(slow, "--backend", "vm")
    time.sleep(1)
    write(slow, BALL.replace("RADIUS", "0.5"))
    st = s.wait_state(lambda st: st.get("version", 0) >= 1, 60)
    check("a save during a long frame: the new scene runs", st.get("ok") is True, str(st)[:300])
    write(slow, slow_text)
    time.sleep(1)
    code, out, err = s.stop()
    check("Ctrl-C during a long frame ends the server", code == 0, f"{code} {err[-300:]!r}")
    # A script that loops 9 million times at every point: one batch of evaluations would take
    # minutes to hours, so every backend's code asks for the cancel in its loops.
    write(slow, slow_text.replace("i < 10000", "i < 9000000"))
    backends = ["vm", "sse"] + (["llvm"] if os.environ.get("FS_HAVE_LLVM", "1") == "1" else [])
    for backend in backends:
        s = Server(slow, "--max-seconds", "1", "--backend", backend)
        st = s.wait_state(lambda st: "took longer" in st.get("diagnostics", ""), 60)
        check(f"--serve --max-seconds, {backend}: a script's long loop stops within an iteration",
              st.get("ok") is False and "took longer than 1 s" in st.get("diagnostics", ""), str(st)[:300])
        code, out, err = s.stop()
        check(f"--serve --max-seconds, {backend}: Ctrl-C ends it cleanly", code == 0, f"{code} {err[-300:]!r}")

    # A scene broken from the start: no glTF yet, the diagnostics, and the server runs on.
    write(scene, BALL.replace("RADIUS", "0.5 *"))
    s = Server(scene)
    st = s.wait_state(lambda st: st.get("version", 0) >= 1, 30)
    check("a scene broken at the start: its diagnostics", st.get("ok") is False and "error:" in st.get("diagnostics", ""))
    status, _ = s.request("GET", "/scene.glb")
    check("a scene broken at the start: no glTF yet", status == 404, str(status))
    busy = subprocess.run([RUN, scene, "--serve", "--port", str(s.port)], capture_output=True, text=True, timeout=30)
    check("a port in use: a clear error", busy.returncode == 1 and "cannot listen" in busy.stderr, busy.stderr[-200:])
    code, out, err = s.stop()
    check("Ctrl-C ends it cleanly (broken scene)", code == 0, f"{code} {err[-300:]!r}")
    missing = subprocess.run([RUN, os.path.join(d, "nosuch.wrl"), "--serve", "--port", "0"], capture_output=True,
                             text=True, timeout=30)
    check("a scene that is not there: an error at the start", missing.returncode == 1 and
          "nosuch.wrl:1:1: error: cannot read the file: No such file or directory" in missing.stderr and
          "serving" not in missing.stdout, missing.stdout + missing.stderr)
    bad = subprocess.run([RUN, scene, "--serve", "-o", os.path.join(d, "x.glb")], capture_output=True, text=True, timeout=30)
    check("--serve with -o: refused", bad.returncode == 2 and "--serve writes no file" in bad.stderr, bad.stderr)

with tempfile.TemporaryDirectory() as folder:
    try:
        main(folder)
    finally:
        for p in started:
            if p.poll() is None:
                p.kill()
print(f"{checks - fails} of {checks} serve checks passed")
sys.exit(1 if fails else 0)
