#!/usr/bin/env python3
"""Hostile inputs through the real `vtouching` binary (issue #14, docs/RELIABILITY.md).

Each case builds its bad input in its own folder, runs the binary under a memory ceiling
(RLIMIT_AS, as `ulimit -v`) and a time limit, and checks the exit code, that a failure is one
line on stderr naming what it should, and what is left on disk. Usage:
  hostile.py VTOUCHING SOURCE_DIR WORK_DIR --list | CASE...
Exit 0 = pass, 1 = fail, 77 = skipped (needs root to mount a small tmpfs, ...).
"""
import os
import re
import shutil
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
from support import *  # noqa: F401,F403 (the registry, Ctx and the input builders)
import bounds_cases  # noqa: F401 (registers its cases)
import process_cases  # noqa: F401

# --- 1: glTF loader crashes --------------------------------------------------------------

@case
def gltf_accessor_count_wraps(ctx):
    ctx.refuse(render_scene(ctx, ctx.write("bad.gltf", gltf(count=6148914691236517206))), r"bad\.gltf.*POSITION accessor .*past the end")


@case
def gltf_index_count_2p63(ctx):
    ctx.refuse(render_scene(ctx, ctx.write("bad.gltf", gltf(index_count=2**63))), r"bad\.gltf.*indices accessor .*past the end")


# --- 2: unbounded work from small files ---------------------------------------------------

@case
def gltf_node_fanout(ctx):
    nodes = [{"children": [i + 1, i + 1]} for i in range(60)] + [{"mesh": 0}]
    ctx.refuse(render_scene(ctx, ctx.write("fan.gltf", gltf(nodes=nodes))), r"fan\.gltf.*100000 node visits", mem_mb=512, timeout=30)


@case
def gltf_mesh_instances(ctx):
    """697 bytes of glTF and a 480 KB .bin: one 40960-vertex mesh under 2^15 node visits (within the
    visit budget) asked for 1.3 G vertices, copied per visit."""
    import json
    ctx.write("inst/mesh.bin", b"\0" * (12 * 40960))
    doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
           "nodes": [{"children": [i + 1, i + 1]} for i in range(15)] + [{"mesh": 0}],
           "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
           "buffers": [{"uri": "mesh.bin", "byteLength": 12 * 40960}], "bufferViews": [{"buffer": 0, "byteLength": 12 * 40960}],
           "accessors": [{"bufferView": 0, "componentType": 5126, "count": 40960, "type": "VEC3"}]}
    scene = ctx.write("inst/inst.gltf", json.dumps(doc))
    ctx.refuse(render_scene(ctx, scene), r"inst\.gltf.*32768 mesh instances hold more than 8388608 vertices", mem_mb=512, timeout=30)


@case
def gltf_nan_position(ctx):
    ctx.refuse(render_scene(ctx, ctx.write("nan.gltf", gltf(positions=[float("nan")] + QUAD_FLOATS[1:]))),
               r"nan\.gltf.*POSITION element 0 is NaN or infinite")


@case
def option_nan_length(ctx):
    ctx.refuse(["acquire", "--synthetic", "pattern_board", "--out", ctx.path("X"), "--length-mm", "nan", "--lines", "2"],
               r"--length-mm must be a finite number", timeout=20)


@case
def option_inf_noise(ctx):
    ctx.refuse(["acquire", "--synthetic", "pattern_board", "--out", ctx.path("X"), "--noise-g", "inf"], r"--noise-g must be a finite")


@case
def option_nan_fps(ctx):
    ctx.refuse(["render", "--trajectory", ctx.slide, "--out", ctx.path("o"), "--fps", "nan"], r"--fps must be a finite")


@case
def option_nan_seconds(ctx):
    ctx.refuse(["serve", "--seconds", "nan"], r"--seconds must be a finite")


@case
def option_1e300_scale(ctx):
    ctx.refuse(["acquire", "--synthetic", "pattern_board", "--out", ctx.path("X"), "--scale", "1e300"], r"--scale .* out of range")


@case
def option_1e300_seconds(ctx):
    ctx.refuse(["client", "--connect", "127.0.0.1:9", "--headless", "--seconds", "1e300"], r"--seconds 1e\+300 out of range")


@case
def config_error_names_option(ctx):
    ctx.refuse(["render", "--trajectory", ctx.slide, "--out", ctx.path("o"), "--fps", "0", "--rate", "5"],
               r"render: --rate 5: haptics config: rate_hz 5 outside")


@case
def option_1e400(ctx):
    ctx.refuse(["acquire", "--synthetic", "pattern_board", "--out", ctx.path("X"), "--length-mm", "1e400"], r"--length-mm .*out of range")


@case
def option_huge_top_view(ctx):
    ctx.refuse(["acquire", "--synthetic", "pattern_board", "--out", ctx.path("X"), "--length-mm", "1000", "--scale", "100"],
               r"top view .* over the limit")


@case
def robot_log_runaway_span(ctx):
    scan = synthetic_scan(ctx)
    robot = os.path.join(scan, "lines/line_000_robot.csv")
    rows = open(robot).read().split("\n")
    out = [rows[0]]
    for row in rows[1:]:
        if row:
            p, t, x, y, z = row.split(",")
            out.append(f"{p},{t},{x},{2e4 * float(t):.7f},{z}")
    open(robot, "w").write("\n".join(out) + "\n")
    ctx.refuse(["acquire", scan, "--out", ctx.path("ds"), "--quiet"],
               r"line_000_robot\.csv \(line 0\): the stylus covers .* m along the scan line, over the limit of 1e\+06 taxels", mem_mb=512)


@case
def recording_huge_path_length(ctx):
    body = recording().replace("gltf=0:", "gltf=2000000000:x")
    ctx.refuse(["replay", ctx.write("r.rec", body)], r"r\.rec: line 2: scene line: gltf path length 2000000000 is over the limit",
               mem_mb=512)


@case
def recording_endless_line(ctx):
    ctx.refuse(["replay", ctx.write("r.rec", "vtouching-recording 3\n" + "P " + "1" * 200000)], r"longer than the limit", mem_mb=512)


@case
def trajectory_too_long(ctx):
    t = ctx.write("long.csv", "t_s,x_m,y_m,z_m\n0,0,0.1,0\n1000000,0,0.1,0\n")
    ctx.refuse(["render", "--trajectory", t, "--out", ctx.path("o"), "--fps", "0"], r"long\.csv.*over the limit of 3600 s")


@case
def png_100000_header(ctx):
    ctx.write("huge/huge/huge.png", png(100000, 100000, rows=b"\0"))
    ctx.write("huge/huge/huge_acc.png", png(100000, 100000, rows=b"\0"))
    ctx.refuse(["render", "--trajectory", ctx.slide, "--out", ctx.path("o"), "--fps", "0", "--dataset", ctx.path("huge")],
               r"huge\.png.*100000x100000 pixels is over the limit")


@case
def png_16384_square(ctx):
    ctx.write("big/big/big.png", png(16384, 16384, colour=0))
    ctx.write("big/big/big_acc.png", png(16384, 16384, colour=0))
    ctx.refuse(["render", "--trajectory", ctx.slide, "--out", ctx.path("o"), "--fps", "0", "--dataset", ctx.path("big")],
               r"big\.png.*16384x16384 pixels is over the limit", mem_mb=512)


@case
def dataset_mm_per_pixel_1e308(ctx):
    ctx.write("d/a/a.png", png(8, 8))
    ctx.write("d/a/a_acc.png", png(8, 8))
    ctx.write("d/a/a_map.json", '{"mm_per_pixel": 1e308}')
    ctx.refuse(["render", "--trajectory", ctx.slide, "--out", ctx.path("o"), "--fps", "0", "--dataset", ctx.path("d")],
               r"a_map\.json.*mm_per_pixel.*\[0\.001, 100\]")


# --- 3: partial or mixed outputs ----------------------------------------------------------

@case
def dataset_exists_without_force(ctx):
    scan = synthetic_scan(ctx)
    ctx.succeed(["acquire", scan, "--out", ctx.path("ds"), "--quiet"])
    ctx.refuse(["acquire", scan, "--out", ctx.path("ds"), "--quiet"], r"ds/plastic_grid' already exists \(use --force")
    ctx.succeed(["acquire", scan, "--out", ctx.path("ds"), "--quiet", "--force", "--no-float-map"])
    left = sorted(os.listdir(ctx.path("ds/plastic_grid")))
    assert "plastic_grid_map.f32" not in left, f"a stale float map survived --no-float-map: {left}"
    assert os.listdir(ctx.path("ds")) == ["plastic_grid"], f"temporary folders left: {os.listdir(ctx.path('ds'))}"


@case
def synthetic_scan_exists_without_force(ctx):
    synthetic_scan(ctx)
    ctx.refuse(["acquire", "--synthetic", "plastic_grid", "--out", ctx.path("scan"), "--lines", "2"], r"scan' already exists")


def refill_and_acquire_again(ctx, scan, disk, before, leave_bytes, error, extra=()):
    """Fills `disk` up to `leave_bytes`; acquiring `scan` again with --force (and `extra`) must fail
    with `error` and leave the previous object as `before` and nothing else behind."""
    fill(disk, leave_bytes)
    ctx.refuse(["acquire", scan, "--out", disk, "--quiet", "--force", *extra], error)
    after = folder_contents(os.path.join(disk, "plastic_grid"))
    assert before == after, "the previous dataset object changed"
    assert sorted(os.listdir(disk)) == ["filler", "plastic_grid"], f"left behind: {os.listdir(disk)}"


@case
def full_disk_acquire_keeps_previous(ctx):
    scan = synthetic_scan(ctx)
    with small_disk(ctx, "disk", "2m") as disk:
        ctx.succeed(["acquire", scan, "--out", disk, "--quiet"])
        before = folder_contents(os.path.join(disk, "plastic_grid"))
        refill_and_acquire_again(ctx, scan, disk, before, 8192, r"no space left on the disk")
        # And the intact object still loads.
        os.remove(os.path.join(disk, "filler"))
        ctx.succeed(["render", "--trajectory", ctx.slide, "--out", ctx.path("o"), "--fps", "0", "--dataset", disk])


@case
def full_disk_waveforms_keep_previous(ctx):
    """The disk fills while the waveforms are written (the dataset's last and largest files)."""
    scan = synthetic_scan(ctx)
    with small_disk(ctx, "disk", "2m") as disk:
        ctx.succeed(["acquire", scan, "--out", disk, "--quiet"])
        before = folder_contents(os.path.join(disk, "plastic_grid"))
        rest = sum(len(b) for name, b in before.items() if name != "waveforms/data.bin")
        waves = len(before["waveforms/data.bin"])
        assert waves > 256 * 1024, f"waveforms/data.bin is only {waves} bytes: the case needs it larger than the margin"
        # Room for everything but data.bin (plus a page per file): the failure is in the waveforms step.
        # One job, so the PNGs are written before the waveforms: with more, the writers share the
        # disk at once and whichever meets the full disk first (a PNG, at times) is the one named.
        refill_and_acquire_again(ctx, scan, disk, before, rest + 4096 * len(before) + 65536,
                                 r"waveforms/data\.bin.*no space left on the disk", ["--jobs", "1"])


@case
def dataset_force_no_waveforms(ctx):
    scan = synthetic_scan(ctx)
    ctx.succeed(["acquire", scan, "--out", ctx.path("ds"), "--quiet"])
    assert os.path.isfile(ctx.path("ds/plastic_grid/waveforms/data.bin")), "no waveforms written by default"
    ctx.succeed(["acquire", scan, "--out", ctx.path("ds"), "--quiet", "--force", "--no-waveforms"])
    left = sorted(os.listdir(ctx.path("ds/plastic_grid")))
    assert "waveforms" not in left, f"a stale waveforms/ folder survived --force --no-waveforms: {left}"
    assert "plastic_grid_map.json" in left, left


@case
def full_disk_render_outputs(ctx):
    with small_disk(ctx, "disk", "256k") as disk:
        ctx.refuse(["render", "--trajectory", ctx.slide, "--out", disk, "--fps", "0"], r"traces\.csv.*no space left on the disk")
        assert os.listdir(disk) == [], f"partial outputs left: {os.listdir(disk)}"


@case
def full_disk_png(ctx):
    with small_disk(ctx, "disk", "64k") as disk:
        ctx.refuse(["render", "--out", disk, "--frames", "1", "--size", "640x360"], r"frame\.png.*no space left on the disk")
        assert os.listdir(disk) == [], f"partial outputs left: {os.listdir(disk)}"


@case
def render_replaces_an_earlier_run(ctx):
    out = ctx.path("o")
    os.makedirs(out)
    for stale in ["frame_00099.png", "figure_gone.png"]:
        open(os.path.join(out, stale), "wb").write(png(4, 4))
    open(os.path.join(out, "notes.txt"), "w").write("mine")
    ctx.succeed(["render", "--trajectory", ctx.slide, "--out", out, "--fps", "0"])
    left = sorted(os.listdir(out))
    assert "frame_00099.png" not in left and "figure_gone.png" not in left, f"an earlier run's outputs mixed in: {left}"
    assert "notes.txt" in left and "traces.csv" in left and "figure.png" in left, left
    assert not [f for f in left if f.startswith(".")], f"temporaries left: {left}"


@case
def export_exists_without_force(ctx):
    glb, hjif = ctx.path("scene.glb"), ctx.path("clip.hjif")
    ctx.succeed(["export", "--builtin", "--out", glb])
    ctx.refuse(["export", "--builtin", "--out", glb], r"scene\.glb' already exists \(use --force")
    ctx.succeed(["export", "--builtin", "--out", glb, "--force"])
    rec = ctx.write("rec.csv", ACTUATOR_CSV)
    ctx.succeed(["export", rec, "--out", hjif])
    ctx.refuse(["export", rec, "--out", hjif], r"clip\.hjif' already exists \(use --force")
    ctx.succeed(["export", rec, "--out", hjif, "--force"])
    left = sorted(os.listdir(ctx.dir))
    assert left == ["clip.hjif", "rec.csv", "scene.glb"], f"left behind: {left}"


@case
def full_disk_export_keeps_previous(ctx):
    with small_disk(ctx, "disk", "4m") as disk:
        scene = os.path.join(disk, "scene.gltf")
        ctx.succeed(["export", "--builtin", "--out", scene])
        before = folder_contents(disk)
        assert "scene.bin" in before and "scene.gltf" in before, sorted(before)
        fill(disk, 8192)
        ctx.refuse(["export", "--builtin", "--out", scene, "--force"], r"no space left on the disk")
        after = folder_contents(disk)
        del after["filler"]
        assert before == after, "the previous export changed"
        os.remove(os.path.join(disk, "filler"))
        ctx.succeed(render_scene(ctx, scene))  # and it still loads


@case
def output_under_a_file(ctx):
    f = ctx.write("plain", "x")
    ctx.refuse(["render", "--trajectory", ctx.slide, "--out", f + "/o", "--fps", "0"], r"plain/o")


# --- 4: truncated recordings ---------------------------------------------------------------

@case
def recording_complete_replays(ctx):
    out = ctx.succeed(["replay", ctx.write("r.rec", recording())])
    assert " 0 differ" in out, out


@case
def recording_cut_mid_line(ctx):
    body = recording()
    ctx.refuse(["replay", ctx.write("r.rec", body[: body.rindex("F ") + 5])], r"r\.rec: line 6: cut short.*end record \(E\) is missing")


@case
def recording_without_end(ctx):
    body = recording()
    ctx.refuse(["replay", ctx.write("r.rec", body[: body.index("E ")])], r"r\.rec: ends after line 6 without its end record")


@case
def recording_changed_byte(ctx):
    body = recording().replace("F 1 2000000 0 0 5 0 0", "F 1 2000000 0 0 5 0 1")
    ctx.refuse(["replay", ctx.write("r.rec", body)], r"checksum mismatch")


@case
def recording_nan_config(ctx):
    body = recording(end=False).replace("gain=1", "gain=nan")
    body += f"E {body.count(chr(10))} {fnv(body.encode()):016x}\n"
    ctx.refuse(["replay", ctx.write("r.rec", body)], r"r\.rec: line 3: config line: gain.* NaN")


@case
def recording_old_version(ctx):
    ctx.refuse(["replay", ctx.write("r.rec", recording(version=1, end=False))], r"older version \(without the hand times the replay needs\); record it again")


# --- 5: degenerate geometry ---------------------------------------------------------------

def scan_with_perspective(ctx, matrix):
    import json
    scan = synthetic_scan(ctx)
    doc = json.load(open(os.path.join(scan, "scan.json")))
    doc["perspective"]["matrix"] = matrix
    json.dump(doc, open(os.path.join(scan, "scan.json"), "w"))
    return scan


@case
def perspective_zeros(ctx):
    ctx.refuse(["acquire", scan_with_perspective(ctx, [0] * 9), "--out", ctx.path("ds")], r"scan\.json.*perspective\.matrix' is all zeros")


@case
def perspective_1e308(ctx):
    ctx.refuse(["acquire", scan_with_perspective(ctx, [1e308] * 9), "--out", ctx.path("ds")], r"perspective\.matrix' is singular")


@case
def calibration_on_one_line(ctx):
    scan = synthetic_scan(ctx)
    rows = ["x_m,y_m,u_px,v_px"] + [f"{0.3 + i * 0.001:.4f},{-0.04:.4f},{100 + 10 * i},{200}" for i in range(10)]
    open(os.path.join(scan, "calibration.csv"), "w").write("\n".join(rows) + "\n")
    ctx.refuse(["acquire", scan, "--out", ctx.path("ds")], r"calibration\.csv.*do not span an area on the object")


# --- 6: paths escaping the scene folder ----------------------------------------------------

@case
def gltf_buffer_outside(ctx):
    ctx.refuse(render_scene(ctx, ctx.write("s/scene.gltf", gltf(buffer_uri="../../../../../../etc/passwd"))),
               r"scene\.gltf.*etc/passwd' is outside the scene folder")


@case
def gltf_buffer_symlink_outside(ctx):
    scene = ctx.write("s/scene.gltf", gltf(buffer_uri="data.bin"))
    os.symlink("/etc/passwd", ctx.path("s/data.bin"))
    ctx.refuse(render_scene(ctx, scene), r"data\.bin' is outside the scene folder")


@case
def gltf_vibration_map_outside(ctx):
    ctx.write("x.png", png(4, 4))
    scene = ctx.write("s/scene.gltf", gltf(extras={"vibration_map": "../x.png"}))
    ctx.refuse(render_scene(ctx, scene), r"vibration_map '.*x\.png' is outside the scene folder")
    ctx.succeed(render_scene(ctx, scene, "--allow-outside-paths"))  # the user's way to allow it


@case
def gltf_image_outside(ctx):
    ctx.write("x.png", png(4, 4))
    ctx.refuse(render_scene(ctx, ctx.write("s/scene.gltf", gltf(textures="../x.png"))), r"x\.png' is outside the scene folder")


# --- 7: one-line messages ------------------------------------------------------------------

@case
def symlink_loop_scene(ctx):
    os.symlink("loop.gltf", ctx.path("loop.gltf"))
    ctx.refuse(render_scene(ctx, ctx.path("loop.gltf")), r"loop\.gltf.*symbolic links \(a symlink loop\?\)")


@case
def symlink_loop_trajectory(ctx):
    os.symlink("t.csv", ctx.path("t.csv"))
    ctx.refuse(["render", "--trajectory", ctx.path("t.csv"), "--out", ctx.path("o"), "--fps", "0"], r"t\.csv.*symlink loop")


@case
def folder_as_scene(ctx):
    os.makedirs(ctx.path("dir.gltf"))
    ctx.refuse(render_scene(ctx, ctx.path("dir.gltf")), r"dir\.gltf': is a folder, expected a file")


@case
def folder_as_map_json(ctx):
    ctx.write("d/a/a.png", png(8, 8))
    ctx.write("d/a/a_acc.png", png(8, 8))
    os.makedirs(ctx.path("d/a/a_map.json"))
    ctx.refuse(["render", "--trajectory", ctx.slide, "--out", ctx.path("o"), "--fps", "0", "--dataset", ctx.path("d")],
               r"a_map\.json': is a folder, expected a file")


@case
def folder_as_scan_json(ctx):
    os.makedirs(ctx.path("scan/scan.json"))
    ctx.refuse(["acquire", ctx.path("scan"), "--out", ctx.path("ds")], r"scan\.json': is a folder")


@case
def folder_as_haptic_file(ctx):
    os.makedirs(ctx.path("dir.hjif"))
    ctx.refuse(["play", ctx.path("dir.hjif"), "--glove", "none"], r"haptic file '.*dir\.hjif': is a folder, expected a file")


@case
def symlink_loop_haptic_file(ctx):
    os.symlink("loop.ahap", ctx.path("loop.ahap"))
    ctx.refuse(["play", ctx.path("loop.ahap"), "--glove", "none"], r"loop\.ahap': cannot read: too many levels of symbolic links")


@case
def oversized_haptic_file(ctx):
    with open(ctx.path("big.haptic"), "wb") as f:
        f.truncate((128 << 20) + 1)  # sparse
    ctx.refuse(["play", ctx.path("big.haptic"), "--glove", "none"], r"big\.haptic': 134217729 bytes is over the limit", mem_mb=512)


@case
def folder_as_recording_csv(ctx):
    os.makedirs(ctx.path("dir.csv"))
    ctx.refuse(["export", ctx.path("dir.csv"), "--out", ctx.path("x.hjif")], r"actuator CSV '.*dir\.csv': is a folder")
    assert not os.path.exists(ctx.path("x.hjif"))


@case
def symlink_loop_recording_wav(ctx):
    os.symlink("loop.wav", ctx.path("loop.wav"))
    ctx.refuse(["export", ctx.write("rec.csv", ACTUATOR_CSV), ctx.path("loop.wav"), "--out", ctx.path("x.hjif")],
               r"WAV '.*loop\.wav': cannot read: too many levels of symbolic links")


@case
def oversized_recording_wav(ctx):
    with open(ctx.path("big.wav"), "wb") as f:
        f.truncate((128 << 20) + 1)
    ctx.refuse(["export", ctx.path("big.wav"), "--out", ctx.path("x.hjif")], r"big\.wav': 134217729 bytes is over the limit",
               mem_mb=512)


@case
def folder_as_gains(ctx):
    os.makedirs(ctx.path("gains.csv"))
    ctx.refuse(["render", "--trajectory", ctx.slide, "--out", ctx.path("o"), "--fps", "0", "--dataset", tiny_dataset(ctx),
                "--gains", ctx.path("gains.csv")], r"gain table '.*gains\.csv': is a folder, expected a file")


@case
def symlink_loop_gains(ctx):
    os.symlink("gains.csv", ctx.path("gains.csv"))
    ctx.refuse(["export", tiny_dataset(ctx), "--out", ctx.path("x.glb"), "--gains", ctx.path("gains.csv")],
               r"gain table '.*gains\.csv': cannot read: too many levels")
    assert not os.path.exists(ctx.path("x.glb"))


@case
def permission_denied(ctx):
    if os.geteuid() != 0:
        user = None  # already unprivileged: mode 000 is enough
    else:
        user = 65534  # root reads everything: run the binary as nobody
        os.chmod(ctx.dir, 0o755)
    t = ctx.write("t.csv", "t_s,x_m,y_m,z_m\n0,0,0.1,0\n1,0,0.1,0\n")
    os.chmod(t, 0)
    os.chmod(ctx.dir, 0o777)
    ctx.refuse(["render", "--trajectory", t, "--out", ctx.path("o"), "--fps", "0"], r"t\.csv': cannot read: permission denied", user=user)


@case
def gltf_parse_error_one_line(ctx):
    ctx.refuse(render_scene(ctx, ctx.write("broken.gltf", '{"asset": {"version": "2.0"}, "buffers": [')), r"broken\.gltf.*not a valid glTF")


@case
def gltf_missing_buffer_one_line(ctx):
    ctx.refuse(render_scene(ctx, ctx.write("s/m.gltf", gltf(buffer_uri="missing.bin"))), r"m\.gltf.*not found : missing\.bin")


@case
def repeated_option(ctx):
    ctx.refuse(["render", "--trajectory", ctx.slide, "--out", ctx.path("o"), "--gain", "1", "--gain", "2"], r"option --gain given more than once")


@case
def repeated_flag(ctx):
    ctx.refuse(["acquire", "x", "--out", ctx.path("o"), "--quiet", "--quiet"], r"option --quiet given more than once")


@case
def help_every_command(ctx):
    """Every command `vtouching help` lists prints its own usage for --help."""
    commands = re.findall(r"^  (\w[\w-]*) ", ctx.succeed(["help"]), re.M)
    assert len(commands) >= 10 and "play" in commands and "export" in commands, f"commands parsed from help: {commands}"
    for command in commands:
        out = ctx.succeed([command, "--help"])
        assert out.startswith(f"usage: vtouching {command}"), f"{command} --help: {out[:300]}"
    print("usage printed by:", " ".join(commands))


def main():
    if len(sys.argv) >= 2 and sys.argv[1] == "--list":
        print(";".join(CASES))
        return 0
    exe, source, work, names = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
    status = 0
    for name in names:
        folder = os.path.join(work, name)
        shutil.rmtree(folder, ignore_errors=True)
        os.makedirs(folder)
        try:
            CASES[name](Ctx(exe, source, folder))
            print(f"PASS {name}")
        except Skip as s:
            print(f"SKIPPED {name}: {s}")
            status = status or SKIP
        except AssertionError as e:
            print(f"FAIL {name}: {e}")
            status = 1
    return status


if __name__ == "__main__":
    sys.exit(main())
