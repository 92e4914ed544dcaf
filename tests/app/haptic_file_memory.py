#!/usr/bin/env python3
"""Haptic files at the documented limits through the real binary, under an address-space cap
(issue #27; docs/haptic-files.md "Limits and memory"): the longest recording (a 96 MB WAV, 10
actuators at 8 kHz for 600 s) converts to every format in bounded memory, clips too large for
one file are split into parts that `play` reads, and reading a part near the 128 MiB file limit
stays within its documented bound. Usage: haptic_file_memory.py VTOUCHING SOURCE_DIR WORK_DIR CASE
(uses tests/hostile/hostile.py's runner: exit 0 pass, 1 fail)."""
import math
import os
import struct
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "hostile"))
from hostile import Ctx  # noqa: E402

MIB = 1 << 20
CASES = {}


def case(fn):
    CASES[fn.__name__] = fn
    return fn


def wav(path, channels, seconds, rate=8000):
    """A PCM16 WAV whose channels carry 250 Hz sines under different slow envelopes (one second
    generated, then repeated: enough texture that nothing collapses in the writers)."""
    second = bytearray()
    for i in range(rate):
        for c in range(channels):
            level = 0.2 + 0.7 * abs(math.sin(math.pi * (i / rate) * (c + 1)))
            second += struct.pack("<h", int(32767 * level * math.sin(2 * math.pi * 250 * i / rate + c)))
    data = bytes(second) * seconds
    with open(path, "wb") as f:
        f.write(b"RIFF" + struct.pack("<I", 36 + len(data)) + b"WAVEfmt " +
                struct.pack("<IHHIIHH", 16, 1, channels, rate, rate * channels * 2, channels * 2, 16) +
                b"data" + struct.pack("<I", len(data)))
        f.write(data)
    return path


def sizes(ctx, prefix):
    return {n: os.path.getsize(ctx.path(n)) for n in os.listdir(ctx.dir) if n.startswith(prefix)}


@case
def longest_recording_converts_in_bounded_memory(ctx):
    big = wav(ctx.path("rec.wav"), 10, 600)  # 96 MB: the documented maximum recording
    assert os.path.getsize(big) == 96_000_044
    for ext in (".ahap",):  # the larger of the two envelope formats (.haptic: tests/haptics)
        out = ctx.succeed(["convert", big, "--out", ctx.path("rec" + ext)], mem_mb=1024)
        files = sizes(ctx, "rec-")
        written = [n for n in files if n.endswith(ext)]
        assert len(written) == 10, f"{ext}: {written}"  # one per actuator, 600 s each: no split needed
        assert max(files[n] for n in written) <= 128 * MIB
        assert "lost: the waveform is not carried" in out
        ctx.succeed(["play", ctx.path("rec-palm-little-down" + ext), "--glove", "none"], mem_mb=1024)
    out = ctx.succeed(["convert", big, "--out", ctx.path("copy.wav")], mem_mb=1024)
    with open(big, "rb") as a, open(ctx.path("copy.wav"), "rb") as b:
        assert a.read() == b.read(), "WAV -> WAV is not byte for byte"


@case
def waveform_too_large_for_one_hjif_is_split_into_playable_parts(ctx):
    one = wav(ctx.path("one.wav"), 1, 600)  # 9.6 MB: took 4.1 GB to export before
    out = ctx.succeed(["convert", one, "--out", ctx.path("one.hjif")], mem_mb=1024)
    parts = sorted(n for n in sizes(ctx, "one-part") if n.endswith(".hjif"))
    assert len(parts) >= 2 and "split into" in out, out
    assert all(os.path.getsize(ctx.path(n)) <= 128 * MIB for n in parts)
    largest = max(parts, key=lambda n: os.path.getsize(ctx.path(n)))
    assert os.path.getsize(ctx.path(largest)) > 64 * MIB  # parts are sized from a byte bound ~2x the real size
    # Reading and playing it: the file, its packed keyframes and the clip (a 118 MiB HJIF took 2.2 GB).
    ctx.succeed(["play", ctx.path(largest), "--glove", "none"], mem_mb=1024)
    # The parts joined are the recording again.
    for n in parts:
        ctx.succeed(["convert", ctx.path(n), "--out", ctx.path("back-" + n.replace(".hjif", ".wav"))], mem_mb=1024)
    # (each part's WAV has a channel per actuator: the thumb's is channel 0 of 10)
    joined = b"".join(memoryview(open(ctx.path("back-" + n.replace(".hjif", ".wav")), "rb").read()[44:]).cast("h")[::10].tobytes()
                      for n in parts)
    assert joined == open(one, "rb").read()[44:], "the parts do not join into the recording"


def main():
    if sys.argv[1:2] == ["--list"]:
        print(";".join(CASES))
        return 0
    exe, source, work, name = sys.argv[1:5]
    path = os.path.join(work, name)
    os.makedirs(path, exist_ok=True)
    for n in os.listdir(path):
        os.remove(os.path.join(path, n))
    CASES[name](Ctx(exe, source, path))
    print("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
