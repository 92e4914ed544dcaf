"""The hostile suite's machinery (docs/RELIABILITY.md): the case registry, the context that runs
`vtouching` under a memory ceiling and a time limit, and the bad inputs the cases build."""
import base64
import contextlib
import os
import re
import resource
import shutil
import struct
import subprocess
import sys
import zlib

SKIP = 77
CASES = {}
NO_DISPLAY = {"DISPLAY": None, "WAYLAND_DISPLAY": None}  # Ctx.run(env=...): `run` renders its offscreen demo


def case(fn):
    CASES[fn.__name__] = fn
    return fn


class Skip(Exception):
    pass


class Ctx:
    def __init__(self, exe, source, work):
        self.exe, self.source, self.dir = exe, source, work
        self.slide = os.path.join(source, "assets/trajectories/slide.csv")

    def path(self, *parts):
        return os.path.join(self.dir, *parts)

    def write(self, name, data):
        path = self.path(name)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "wb") as f:
            f.write(data.encode() if isinstance(data, str) else data)
        return path

    def environment(self, env=None, mem_mb=1024):
        """The binary's environment: `env` adds variables (None removes one); under ASan the
        memory ceiling is ASan's own resident limit (see limits())."""
        out = dict(os.environ, VT_LOG="warn")
        for key, value in (env or {}).items():
            if value is None:
                out.pop(key, None)
            else:
                out[key] = value
        if os.environ.get("VT_HOSTILE_ASAN") == "1":
            # ASan's quarantine of freed blocks (256 MB by default) would count against the
            # ceiling: a loader that frees as it goes reached 420 MB resident under ASan.
            out["ASAN_OPTIONS"] = ":".join(filter(None, [os.environ.get("ASAN_OPTIONS"),
                                                         f"hard_rss_limit_mb={3 * mem_mb}:quarantine_size_mb=32"]))
        return out

    @staticmethod
    def limits(mem_mb, user=None):
        # ASan reserves terabytes of shadow address space, so an address-space ceiling stops it at
        # start-up: under ASan the ceiling is on resident memory, enforced by ASan itself (with room
        # for its shadow and quarantine).
        def apply():
            if os.environ.get("VT_HOSTILE_ASAN") != "1":
                limit = mem_mb << 20
                resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
            if user is not None:
                os.setgid(user)
                os.setuid(user)
        return apply

    def run(self, *args, mem_mb=1024, timeout=120, user=None, env=None):
        try:
            p = subprocess.run([self.exe, *args], cwd=self.dir, env=self.environment(env, mem_mb),
                               preexec_fn=self.limits(mem_mb, user), timeout=timeout,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        except subprocess.TimeoutExpired:
            raise AssertionError(f"timed out after {timeout} s (a hang or unbounded work): {' '.join(args)}")
        return p.returncode, p.stdout.decode(errors="replace"), p.stderr.decode(errors="replace")

    def start(self, *args, mem_mb=1024, env=None):
        """The binary started in the background (signal cases); its stderr is a pipe."""
        return subprocess.Popen([self.exe, *args], cwd=self.dir, env=self.environment(env, mem_mb),
                                preexec_fn=self.limits(mem_mb), stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)

    @staticmethod
    def one_line(code, err, pattern):
        """A failure: exit 1 and exactly one stderr line matching `pattern` (returned)."""
        lines = [l for l in err.split("\n") if l.strip()]
        assert code == 1, f"exit {code} (expected 1; 139 = crash, 137 = killed); stderr: {err[-400:]}"
        assert len(lines) == 1, f"{len(lines)} stderr lines (expected one): {err[-600:]}"
        assert re.search(pattern, lines[0]), f"message does not match /{pattern}/: {lines[0]}"
        print("refused as expected:", lines[0])
        return lines[0]

    def refuse(self, args, pattern, **kw):
        """The run fails with exit 1 and exactly one stderr line matching `pattern`."""
        code, out, err = self.run(*args, **kw)
        return self.one_line(code, err, pattern)

    def succeed(self, args, **kw):
        code, out, err = self.run(*args, **kw)
        assert code == 0, f"exit {code}; stderr: {err[-600:]}"
        return out


# --- inputs ------------------------------------------------------------------------------

def png(width, height, rows=None, colour=2):
    """A PNG with the given header; `rows` = raw scanlines (None: one all-zero IDAT for the size)."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    channels = {0: 1, 2: 3, 6: 4}[colour]
    if rows is None:
        row = b"\0" * (1 + width * channels)
        comp = zlib.compressobj(9)
        data = b"".join(comp.compress(row) for _ in range(height)) + comp.flush()
    else:
        data = zlib.compress(rows)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, colour, 0, 0, 0)) +
            chunk(b"IDAT", data) + chunk(b"IEND", b""))


QUAD_FLOATS = [-0.05, 0, 0.05, 0.05, 0, 0.05, 0.05, 0, -0.05, -0.05, 0, -0.05]


def gltf(positions=None, count=4, index_count=6, buffer_uri=None, extras=None, nodes=None, textures=False):
    """The fuzz corpus' quad, with the fields a case changes."""
    pos = struct.pack("<12f", *(positions or QUAD_FLOATS))
    uv = struct.pack("<8f", 0, 1, 1, 1, 1, 0, 0, 0)
    idx = struct.pack("<6H", 0, 1, 2, 0, 2, 3)
    blob = pos + uv + idx
    uri = buffer_uri or "data:application/octet-stream;base64," + base64.b64encode(blob).decode()
    material = {"name": "m", "extras": {"vtouching": extras or {"gain": 0.7}}}
    doc = {
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": nodes or [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 0}]}],
        "materials": [material],
        "buffers": [{"uri": uri, "byteLength": len(blob)}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 32},
                        {"buffer": 0, "byteOffset": 80, "byteLength": 12}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": count, "type": "VEC3"},
                      {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
                      {"bufferView": 2, "componentType": 5123, "count": index_count, "type": "SCALAR"}],
    }
    if textures:
        doc["materials"][0]["pbrMetallicRoughness"] = {"baseColorTexture": {"index": 0}}
        doc["textures"] = [{"source": 0}]
        doc["images"] = [{"uri": textures}]
    import json
    return json.dumps(doc)


def render_scene(ctx, scene, *extra):
    return ["render", "--trajectory", ctx.slide, "--out", ctx.path("o"), "--fps", "0", "--scene", scene, *extra]


def synthetic_scan(ctx, name="scan", lines="2"):
    ctx.succeed(["acquire", "--synthetic", "plastic_grid", "--out", ctx.path(name), "--lines", lines, "--quiet"])
    return ctx.path(name)


FNV_OFFSET, FNV_PRIME = 0xcbf29ce484222325, 0x100000001b3


def fnv(data, h=FNV_OFFSET):
    for b in data:
        h = ((h ^ b) * FNV_PRIME) & 0xFFFFFFFFFFFFFFFF
    return h


def recording(frames=3, version=3, end=True):
    lines = [f"vtouching-recording {version}", "scene mm_per_pixel=0 builtin=1 gltf=0: dataset=0:",
             "config rate_hz=1000 model=paper mapping=five gain=1 pose_timeout_ms=50 sampling=predict latency_ms=0"]
    lines += [f"F {i} {1000000 * (i + 1)} 0 0 5 0 0 0 0 0" for i in range(frames)]
    body = "".join(l + "\n" for l in lines)
    return sealed(body) if end else body


def sealed(body):
    """A recording's lines with their end record (line count and checksum) appended."""
    return body + f"E {body.count(chr(10))} {fnv(body.encode()):016x}\n"


@contextlib.contextmanager
def small_disk(ctx, name, size):
    """A tmpfs of `size` mounted at ctx.path(name) for the block, unmounted after it (root only)."""
    if os.geteuid() != 0:
        raise Skip("needs root to mount a small tmpfs (full-disk case)")
    where = ctx.path(name)
    os.makedirs(where, exist_ok=True)
    if subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={size}", "tmpfs", where]).returncode != 0:
        raise Skip("cannot mount a tmpfs here (full-disk case)")
    try:
        yield where
    finally:
        subprocess.run(["umount", where])


def fill(where, leave_bytes):
    st = os.statvfs(where)
    free = st.f_bavail * st.f_frsize
    with open(os.path.join(where, "filler"), "wb") as f:
        f.write(b"\0" * max(0, free - leave_bytes))


def folder_contents(folder):
    """Every file under folder (sub-folders included) by relative path, with its bytes."""
    contents = {}
    for root, _, files in os.walk(folder):
        for name in files:
            path = os.path.join(root, name)
            with open(path, "rb") as f:
                contents[os.path.relpath(path, folder)] = f.read()
    return contents


ACTUATOR_CSV = "t_ns,sequence,thumb,index,thumb_hz,index_hz\n0,0,0,0.5,0,250\n1000000,1,0,0.5,0,250\n2000000,2,0,0,0,250\n"


def tiny_dataset(ctx):
    ctx.write("d/a/a.png", png(8, 8))
    ctx.write("d/a/a_acc.png", png(8, 8))
    ctx.write("d/a/a_map.json", '{"mm_per_pixel": 0.3}')
    return ctx.path("d")
