"""Hostile cases, round three (issue #27): the ffmpeg child of `render --video` (a stall, an early
exit, Ctrl-C, a second signal: clear errors, no orphan), the early-exit paths of render, run,
replay and export (which the ASan build runs for reads of freed state), and key files."""
import os
import signal
import time

from support import NO_DISPLAY, ACTUATOR_CSV, case, recording, sealed, tiny_dataset

def fake_ffmpeg(ctx, body):
    """An `ffmpeg` first on PATH running `body` (sh); it writes its pid to ffmpeg.pid first."""
    script = ctx.write("bin/ffmpeg", f"#!/bin/sh\necho $$ > {ctx.path('ffmpeg.pid')}\n{body}\n")
    os.chmod(script, 0o755)
    return {"PATH": ctx.path("bin") + ":" + os.environ.get("PATH", "/usr/bin:/bin")}


def video_run(ctx, *extra):
    return ["render", "--trajectory", ctx.slide, "--out", ctx.path("o"), "--fps", "5", "--size", "160x90",
            "--video", ctx.path("o", "v.mp4"), "--quiet", *extra]


def assert_gone(ctx, within_s=3.0):
    """The fake ffmpeg (its pid file) is no longer running: no orphan."""
    pid = int(open(ctx.path("ffmpeg.pid")).read())
    deadline = time.time() + within_s
    while time.time() < deadline:
        try:
            os.kill(pid, 0)
        except ProcessLookupError:
            return
        if open(f"/proc/{pid}/stat").read().split()[2] == "Z":  # a zombie of a dead parent: reaped soon
            return
        time.sleep(0.05)
    os.kill(pid, signal.SIGKILL)
    raise AssertionError(f"ffmpeg (pid {pid}) still runs after vtouching ended: an orphan")


def assert_no_partial_outputs(ctx):
    left = os.listdir(ctx.path("o")) if os.path.isdir(ctx.path("o")) else []
    assert not [f for f in left if f.startswith(".") or f.endswith(".partial.mp4") or f in ("traces.csv", "v.mp4")], \
        f"partial outputs left: {left}"


# --- 3: the ffmpeg child -----------------------------------------------------------------------

@case
def ffmpeg_stalls(ctx):
    """An ffmpeg that stops reading blocked the run forever, Ctrl-C ignored."""
    env = fake_ffmpeg(ctx, "exec sleep 300")
    start = time.time()
    ctx.refuse(video_run(ctx), r"render: --video .*v\.mp4: ffmpeg read nothing for 10 s \(stalled\); it was stopped",
               env=env, timeout=60)
    assert time.time() - start < 40, f"took {time.time() - start:.0f} s"
    assert_gone(ctx)
    assert_no_partial_outputs(ctx)


@case
def ffmpeg_exits_mid_run(ctx):
    """ffmpeg ending while frames flow: an error that unwinds a running session (ASan: no freed state)."""
    env = fake_ffmpeg(ctx, "exit 3")
    ctx.refuse(video_run(ctx), r"--video .*v\.mp4: ffmpeg stopped reading frames \(exit status 3", env=env, timeout=60)
    assert_no_partial_outputs(ctx)


def interrupted(ctx, signals, expect_code):
    env = fake_ffmpeg(ctx, "exec sleep 300")
    p = ctx.start(*video_run(ctx), env=env)
    deadline = time.time() + 60
    while not os.path.exists(ctx.path("ffmpeg.pid")) and time.time() < deadline:
        time.sleep(0.05)
    time.sleep(0.5)  # the first frames are written (and blocked)
    for s in signals:
        p.send_signal(s)
        time.sleep(0.05)
    try:
        _, err = p.communicate(timeout=10)
    except Exception:
        p.kill()
        raise AssertionError("vtouching did not end within 10 s of the signal")
    assert p.returncode == expect_code, f"exit {p.returncode} (expected {expect_code}); stderr: {err.decode()[-400:]}"
    assert_gone(ctx)
    return err.decode(errors="replace")


@case
def ffmpeg_ctrl_c(ctx):
    """Ctrl-C ends vtouching and its ffmpeg within seconds, with one line saying so."""
    err = interrupted(ctx, [signal.SIGINT], 1)
    lines = [l for l in err.split("\n") if l.strip()]  # the run's "stopped at" warning, then the error
    assert lines and "ffmpeg did not finish the video after the stop request; it was stopped" in lines[-1], err[-600:]
    assert len(lines) <= 2, err[-600:]
    assert_no_partial_outputs(ctx)


@case
def ffmpeg_second_signal(ctx):
    """A second signal ends vtouching at once: its ffmpeg dies with it (an orphan kept running before)."""
    interrupted(ctx, [signal.SIGINT, signal.SIGINT], 128 + signal.SIGINT)


# --- 2: early exits of render, run, replay, export (run under ASan by the sanitizer build) ---------

@case
def run_demo_out_is_a_file(ctx):
    """`run` without a display: the demo's session is built, then its outputs fail."""
    ctx.refuse(["run", "--demo-out", ctx.write("plain", "x")], r"run: output folder '.*plain' is a file; give a folder",
               env=NO_DISPLAY)


@case
def replay_error_mid_file(ctx):
    """A replay that fails after its session and outputs exist."""
    body = recording(frames=3, end=False) + "F 9 9000000 0 0 5 0 0 0 0\n"
    body = sealed(body)
    ctx.refuse(["replay", ctx.write("r.rec", body), "--out", ctx.path("o"), "--fps", "0"],
               r"r\.rec: line 7: frame intensity 4 is missing")
    assert not os.path.exists(ctx.path("o", "traces.csv"))


@case
def render_record_into_missing_folder(ctx):
    """--record-csv whose folder is a file: the session fails while it is being built."""
    ctx.write("plain", "x")
    ctx.refuse(["render", "--trajectory", ctx.slide, "--out", ctx.path("o"), "--fps", "0", "--record-csv",
                ctx.path("plain", "r.csv")], r"plain/r\.csv': cannot write: a part of the path is not a folder")


@case
def export_recording_fails_at_write(ctx):
    rec = ctx.write("rec.csv", ACTUATOR_CSV)
    ctx.write("plain", "x")
    ctx.refuse(["export", rec, "--out", ctx.path("plain", "x.hjif")], r"plain/x\.hjif")
    ctx.refuse(["export", tiny_dataset(ctx), "--out", ctx.path("plain", "x.glb")], r"plain/x\.glb")


# --- 7: keys ------------------------------------------------------------------------------------

def key_client(ctx, key):
    return ["client", "--connect", "127.0.0.1:9", "--headless", "--seconds", "1", "--key", key]


GOOD_KEY = "5f0c3e9a1b7d2468ace013579bdf2468" "f1e2d3c4b5a69788796a5b4c3d2e1f00"


def key_file(ctx, name, text, mode=0o600):
    path = ctx.write(name, text)
    os.chmod(path, mode)
    return path


@case
def key_file_readable_by_others(ctx):
    ctx.refuse(key_client(ctx, key_file(ctx, "k.key", GOOD_KEY, 0o644)),
               r"key file '.*k\.key': its permissions 0644 let other users read or change the key; make it private with `chmod 600")


@case
def key_all_zeros(ctx):
    ctx.refuse(key_client(ctx, "0" * 64), r"--key: the key is all zeros, so it is not a random key")


@case
def key_short_hex(ctx):
    ctx.refuse(key_client(ctx, "abcd"), r"--key 'abcd': not a key \(a key is 64 hex digits, this has 4\)")


@case
def key_file_with_bom(ctx):
    ctx.refuse(key_client(ctx, key_file(ctx, "bom.key", b"\xef\xbb\xbf" + GOOD_KEY.encode())),
               r"bom\.key'.*starts with a UTF-8 byte-order mark")


@case
def gains_file_utf16(ctx):
    gains = ctx.write("gains.csv", "name,gain\na,1\n".encode("utf-16"))
    ctx.refuse(["render", "--trajectory", ctx.slide, "--out", ctx.path("o"), "--fps", "0", "--dataset", tiny_dataset(ctx),
                "--gains", gains], r"gain table '.*gains\.csv': is UTF-16 text")
