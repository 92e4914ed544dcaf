"""Hostile cases, round three (issue #27): deep JSON, sizes and indices from input held to their
budgets before anything is allocated, outputs that never replace special files nor each other,
leftovers of killed runs, and messages that name what is actually wrong."""
import json
import os
import stat
import time

from support import NO_DISPLAY, ACTUATOR_CSV, Skip, case, gltf, png, recording, render_scene, sealed, synthetic_scan, tiny_dataset

def deep_gltf(ctx, name="deep.gltf"):
    """A valid glTF whose material extras nest 20,000 arrays (SIGSEGV in the JSON reader before)."""
    text = gltf().replace('"extras": {', '"extras": {"deep": ' + "[" * 20000 + "]" * 20000 + ", ", 1)
    return ctx.write(name, text)


def dead_pid():
    """A process id no process has now (the writer of a killed run's temporaries)."""
    pid = 4000000
    while os.path.exists(f"/proc/{pid}"):
        pid -= 1
    return pid


def one_accessor_gltf(ctx, name, count):
    """A glTF of one mesh whose POSITION accessor holds `count` vertices, in a sparse .bin."""
    with open(ctx.path(name + ".bin"), "wb") as f:
        f.truncate(12 * count)
    doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
           "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
           "buffers": [{"uri": name + ".bin", "byteLength": 12 * count}],
           "bufferViews": [{"buffer": 0, "byteLength": 12 * count}],
           "accessors": [{"bufferView": 0, "componentType": 5126, "count": count, "type": "VEC3"}]}
    return ctx.write(name + ".gltf", json.dumps(doc))


# --- 1: bounded everything ---------------------------------------------------------------

@case
def gltf_deep_extras_render(ctx):
    ctx.refuse(render_scene(ctx, deep_gltf(ctx)), r"deep\.gltf.*JSON nested deeper than 64 levels")


@case
def gltf_deep_extras_run(ctx):
    ctx.refuse(["run", "--scene", deep_gltf(ctx), "--demo-out", ctx.path("o")], r"deep\.gltf.*JSON nested deeper than 64",
               env=NO_DISPLAY)


@case
def gltf_deep_extras_hand_model(ctx):
    ctx.refuse(["render", "--trajectory", ctx.slide, "--out", ctx.path("o"), "--fps", "0", "--hand-model", deep_gltf(ctx)],
               r"hand model '.*deep\.gltf'.*JSON nested deeper than 64")


@case
def gltf_material_index_2p32(ctx):
    doc = json.loads(gltf())
    doc["meshes"][0]["primitives"][0]["material"] = 2**32  # loaded as material 0 before
    ctx.refuse(render_scene(ctx, ctx.write("m.gltf", json.dumps(doc))),
               r"m\.gltf.*meshes\[0\]\.primitives\[0\]\.material is 4294967296, which does not fit in 32 bits")


@case
def gltf_texture_index_2p32_plus_k(ctx):
    ctx.write("t.png", png(4, 4))
    doc = json.loads(gltf(textures="t.png"))
    doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"] = 2**32 + 0
    ctx.refuse(render_scene(ctx, ctx.write("t.gltf", json.dumps(doc))), r"baseColorTexture\.index is 4294967296")


@case
def gltf_buffers_name_one_file(ctx):
    """40 buffers naming one 16 MiB file: 640 MiB read for a 16 MiB input before (2.6 GB with 64 MiB)."""
    with open(ctx.path("one.bin"), "wb") as f:
        f.truncate(16 << 20)
    doc = json.loads(gltf())
    doc["buffers"] += [{"uri": "one.bin", "byteLength": 16 << 20} for _ in range(40)]
    ctx.refuse(render_scene(ctx, ctx.write("many.gltf", json.dumps(doc))),
               r"many\.gltf.*the files it references hold more than 536870912 bytes together", mem_mb=1024)


@case
def gltf_vertex_budget_before_allocation(ctx):
    """9 M vertices (108 MB .bin): refused from the accessor's count, before the 400 MB of floats and
    vertices were allocated (1.1 GB with a 512 MiB buffer before)."""
    ctx.refuse(render_scene(ctx, one_accessor_gltf(ctx, "big", 9 * 1000 * 1000)),
               r"big\.gltf.*1 mesh instances hold more than 8388608 vertices", mem_mb=384)


@case
def recording_rows_1e18_apart(ctx):
    """Two rows 10^18 ns apart: export allocated until std::bad_alloc (rc 134) after a minute."""
    rec = ctx.write("rec.csv", "t_ns,sequence,thumb,index,thumb_hz,index_hz\n0,0,0,0.5,0,250\n1000000000000000000,1,0,0.5,0,250\n")
    ctx.refuse(["export", rec, "--out", ctx.path("x.hjif")], r"rec\.csv.*line 3: 1e\+09 s after the first line, past the 3600 s a recording may last",
               mem_mb=512, timeout=30)
    assert not os.path.exists(ctx.path("x.hjif"))


@case
def replay_poses_without_frames(ctx):
    """A recording of 16,385 poses and no actuator frame: held in memory until the next frame before."""
    body = recording(frames=0, end=False)
    pose = " " + " ".join(["0 0 0 0 0 0 1 0.008"] * 26)
    body += "".join(f"P {1000 * (i + 1)} {i + 1} 1{pose}\n" for i in range(16385))
    ctx.refuse(["replay", ctx.write("r.rec", body)], r"r\.rec: line 16388: more than 16384 poses without an actuator frame",
               mem_mb=512)


@case
def gltf_large_mesh_within_bound(ctx):
    """A 48 MB mesh (4 M vertices) loads within 300 MB of address space (docs/RELIABILITY.md: about
    51 bytes per position-only vertex at the peak; the copies made before needed more)."""
    ctx.succeed(render_scene(ctx, one_accessor_gltf(ctx, "large", 4 * 1000 * 1000), "--quiet"), mem_mb=300)


@case
def trajectory_dense_within_bound(ctx):
    """A 20 MB trajectory of 750 k samples loads within 140 MB (a copy of the text and doubling vectors needed more), and its run is not quadratic (each
    tick scanned the samples from the start: hours for a file within the text budget)."""
    rows = "".join(f"{i * 1e-6:.7f},{0.05 * (i % 1000) / 1000:.6f},0.1,0\n" for i in range(750000))
    path = ctx.write("dense.csv", "t_s,x_m,y_m,z_m\n" + rows)
    ctx.succeed(["render", "--trajectory", path, "--out", ctx.path("o"), "--fps", "0", "--builtin", "--quiet"],
                mem_mb=140, timeout=60)


# --- 4: outputs ----------------------------------------------------------------------------

def trajectory_run(ctx, *extra):
    return ["render", "--trajectory", ctx.slide, "--out", ctx.path("o"), "--fps", "0", *extra]


@case
def same_output_twice(ctx):
    ctx.refuse(trajectory_run(ctx, "--record-wav", ctx.path("x"), "--record-csv", ctx.path("x")),
               r"--record-csv and --record-wav both name '.*x': one would overwrite the other")
    assert not os.path.exists(ctx.path("o")) or os.listdir(ctx.path("o")) == [], "the run started"
    assert not os.path.exists(ctx.path("x"))


@case
def record_into_the_traces(ctx):
    ctx.refuse(trajectory_run(ctx, "--record-csv", ctx.path("o", "traces.csv")),
               r"--out \(its traces\.csv\) and --record-csv both name")


@case
def output_fifo_refused(ctx):
    fifo = ctx.path("pipe.csv")
    os.mkfifo(fifo)
    ctx.refuse(trajectory_run(ctx, "--record-csv", fifo), r"pipe\.csv': cannot write: it is a named pipe \(FIFO\)", timeout=30)
    assert stat.S_ISFIFO(os.stat(fifo).st_mode), "the FIFO was replaced"
    assert not os.path.exists(ctx.path("o", "traces.csv"))


@case
def output_device_written_in_place(ctx):
    """As root a renamed temporary replaced /dev/null (or any device) by a regular file."""
    if os.geteuid() != 0:
        raise Skip("needs root to make a device node (a null device of its own; /dev/null is never at stake)")
    device = ctx.path("null")
    os.mknod(device, 0o666 | stat.S_IFCHR, os.makedev(1, 3))
    ctx.succeed(trajectory_run(ctx, "--record-wav", device, "--record-csv", device, "--record", device))
    assert stat.S_ISCHR(os.stat(device).st_mode), "the device was replaced by a regular file"
    assert not [f for f in os.listdir(ctx.dir) if f.startswith(".")], f"temporaries left: {os.listdir(ctx.dir)}"


@case
def output_folder_refused_before_running(ctx):
    os.makedirs(ctx.path("rec.csv"))
    ctx.refuse(trajectory_run(ctx, "--record-csv", ctx.path("rec.csv")), r"rec\.csv': cannot write: is a folder")
    assert not os.path.exists(ctx.path("o", "traces.csv"))


@case
def stale_temporaries_removed(ctx):
    os.makedirs(ctx.path("o"))
    stale = ctx.write(f"o/.traces.csv.tmp-{dead_pid()}-0", "half a file from a killed run")
    os.utime(stale, (time.time() - 600, time.time() - 600))  # left ten minutes ago
    code, out, err = ctx.run(*trajectory_run(ctx))
    assert code == 0, err
    assert not os.path.exists(stale), "a killed run's temporary is still there"
    assert "removed" in err and os.path.basename(stale) in err, f"not named: {err}"


@case
def moved_aside_folder_put_back(ctx):
    """A run killed between moving the previous dataset object aside and moving the new one in."""
    scan = synthetic_scan(ctx)
    ctx.succeed(["acquire", scan, "--out", ctx.path("ds"), "--quiet"])
    aside = ctx.path("ds", f".plastic_grid.old-{dead_pid()}-0")
    os.rename(ctx.path("ds", "plastic_grid"), aside)
    os.utime(aside, (time.time() - 600, time.time() - 600))
    code, _, err = ctx.run("acquire", scan, "--out", ctx.path("ds"), "--quiet")
    lines = [l for l in err.split("\n") if l.strip()]  # the restore is logged, then the refusal
    assert code == 1 and len(lines) == 2, f"exit {code}: {err[-600:]}"
    assert "restored" in lines[0] and "left by a run that was killed" in lines[0], lines[0]
    assert "plastic_grid' already exists (use --force" in lines[1], lines[1]
    assert os.path.isfile(ctx.path("ds", "plastic_grid", "plastic_grid.png")), "the previous object was not put back"
    assert os.listdir(ctx.path("ds")) == ["plastic_grid"], os.listdir(ctx.path("ds"))


# --- 6: messages that say what is wrong --------------------------------------------------------

@case
def export_unknown_extension(ctx):
    ctx.refuse(["export", ctx.write("rec.csv", ACTUATOR_CSV), "--out", ctx.path("x.mp3")],
               r"--out '.*x\.mp3': unknown extension '\.mp3': a recording exports to \.hjif, \.ahap or \.haptic")


@case
def export_into_missing_folder(ctx):
    ctx.refuse(["export", "--builtin", "--out", ctx.path("nowhere", "x.glb")], r"x\.glb': cannot write: the folder '.*nowhere' does not exist")


@case
def dataset_is_a_file(ctx):
    ctx.refuse(["render", "--trajectory", ctx.slide, "--out", ctx.path("o"), "--fps", "0", "--dataset", ctx.write("d", "x")],
               r"dataset '.*d': is a file, expected a folder")


@case
def recording_nan_frame(ctx):
    body = recording(end=False).replace("F 1 2000000 0 0 5 0 0 0 0 0", "F 1 2000000 0 0 5 0 nan 0 0 0")
    body = sealed(body)
    ctx.refuse(["replay", ctx.write("r.rec", body), "--out", ctx.path("o"), "--fps", "0"], r"r\.rec: line 5: frame intensity 1 is NaN")
    assert not os.path.exists(ctx.path("o", "traces.csv"))


@case
def recording_names_itself(ctx):
    body = recording(end=False).replace("gltf=0:", f"gltf={len('gone.gltf')}:gone.gltf").replace("builtin=1", "builtin=0")
    body = sealed(body)
    ctx.refuse(["replay", ctx.write("r.rec", body)], r"r\.rec: line 2: the scene it was recorded with: glTF 'gone\.gltf': file not found")


@case
def delay_ms_1e300(ctx):
    ctx.refuse(["client", "--connect", "127.0.0.1:9", "--headless", "--delay-ms", "1e300"], r"--delay-ms 1e\+300 out of range 0\.\.10000")


@case
def out_of_memory_names_the_load(ctx):
    """A scene within every budget, under a ceiling too low for it: the message names the scene."""
    if os.environ.get("VT_HOSTILE_ASAN") == "1":
        raise Skip("under ASan the memory ceiling is ASan's resident limit, which ends the process instead")
    ctx.refuse(render_scene(ctx, one_accessor_gltf(ctx, "fits", 8 * 1000 * 1000)), r"out of memory while loading glTF '.*fits\.gltf'",
               mem_mb=384)
