#!/usr/bin/python3
"""Compares an ALSA file-plugin capture of `--output audio` with the `--record-wav` recording.

usage: compare_audio_capture.py CAPTURE.raw CHANNELS RATE RECORD.wav MAP
MAP: for each capture channel, the WAV channel it should carry ("1,0,-" ...).
Prints the correlation and offset per channel and PASS when every carried channel that has a
signal matches and the capture ends in silence. A channel matches when 0.1 s windows at five
places of its active stretch, each at its best offset, correlate >= 0.99 (normalised) in at
least three of them (the median). Windows through a starved block fall below: on a shared
2-core VM a host stall of the audio thread costs one now and then (0.985 and 0.995 beside three
of 1.0 in a quiet run, 0.969 and 0.933 beside three of 1.0 with a sanitizer build compiling
alongside), while a wrong channel, rate or signal stays far below in every window. With
VT_AUDIO_MATCH=signal (the sanitizer stages, whose slower program starves more blocks) the best
window must reach 0.99 and the median 0.95: the capture carries the recording's signal.
Starved blocks themselves are counted by the output (docs/outputs.md), not judged here.
"""
import os
import struct
import sys

import numpy as np


def read_wav(path):
    data = open(path, "rb").read()
    channels, rate = struct.unpack_from("<HI", data, 22)
    samples = np.frombuffer(data[44:], dtype="<i2").astype(np.float64)
    return rate, samples.reshape(-1, channels)


def main():
    capture_path, channels, rate, wav_path, mapping = sys.argv[1:6]
    channels, rate = int(channels), int(rate)
    captured = np.fromfile(capture_path, dtype="<i2").astype(np.float64)
    captured = captured[: len(captured) // channels * channels].reshape(-1, channels)
    wav_rate, recorded = read_wav(wav_path)
    ratio = rate // wav_rate
    ok = True
    checked = 0
    for c, source in enumerate(mapping.split(",")):
        if source == "-":
            if np.any(captured[:, c]):
                print(f"channel {c}: should be silent")
                ok = False
            continue
        ref = recorded[:, int(source)]
        active = np.flatnonzero(np.abs(ref) > 100)
        if len(active) < wav_rate // 10:
            continue  # this actuator barely played: nothing to compare
        window = wav_rate // 10
        x = captured[:, c]

        def best_match(start):
            r = ref[start : start + window]
            best, best_offset = 0.0, 0
            for offset in range(0, len(x) - window * ratio):
                seg = x[offset : offset + window * ratio : ratio]
                denom = np.sqrt(np.dot(seg, seg) * np.dot(r, r))
                if denom > 0:
                    corr = np.dot(seg, r) / denom
                    if corr > best:
                        best, best_offset = corr, offset
            return best, best_offset

        starts = [active[min(len(active) - 1, max(0, int(len(active) * q) - window // 2))] for q in (0.1, 0.3, 0.5, 0.7, 0.9)]
        matches = [best_match(start) for start in starts]
        median = sorted(m[0] for m in matches)[len(matches) // 2]
        best_offset = matches[2][1]
        # The capture starts when the device opens, the recording with the first frame: the
        # difference is that start-up time plus the output's latency (not the latency alone).
        shift_ms = (best_offset / rate - starts[2] / wav_rate) * 1e3
        print(f"channel {c} (actuator {source}): correlation {' '.join(f'{m[0]:.5f}' for m in matches)} "
              f"(median {median:.5f}), capture lags the recording by {shift_ms:.1f} ms")
        checked += 1
        if os.environ.get("VT_AUDIO_MATCH", "exact") == "signal":
            ok = ok and max(m[0] for m in matches) >= 0.99 and median >= 0.95
        else:
            ok = ok and median >= 0.99
    tail = captured[-rate // 100 :]
    if np.any(tail):
        print("the capture does not end in silence")
        ok = False
    if checked == 0:
        print("no actuator played long enough to compare")
        ok = False
    print("PASS" if ok else "FAIL")
    return 0 if ok else 1


sys.exit(main())
