"""The Python module against the CLI on the same inputs (issue #32): errors, statistics,
acquisition, path sampling, recordings, the codec, haptic files, and examples/fig5.py."""
import json
import os
import subprocess
import sys

import numpy as np
import pytest

import vtouching

EXE = os.environ.get("VTOUCHING", "vtouching")
SOURCE = os.environ.get("VT_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
DATASET = os.path.join(SOURCE, "assets", "dataset")


def cli(*args, check=True):
    p = subprocess.run([EXE, *args], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                       env=dict(os.environ, VT_LOG="warn"))
    if check and p.returncode != 0:
        raise AssertionError(f"vtouching {' '.join(args)}: exit {p.returncode}: {p.stderr[-500:]}")
    return p


TAP = """{"version": {"major": 1, "minor": 0, "patch": 0}, "metadata": {"description": "tap"},
 "signals": {"continuous": {"envelopes": {
   "amplitude": [{"time": 0.0, "amplitude": 0.0}, {"time": 0.1, "amplitude": 0.8}, {"time": 0.3, "amplitude": 0.2}],
   "frequency": [{"time": 0.0, "frequency": 0.4}, {"time": 0.3, "frequency": 0.6}]}}}}"""


def test_errors_carry_the_cli_message(out_dir):
    missing = os.path.join(out_dir, "missing.hjif")
    with pytest.raises(vtouching.Error) as caught:
        vtouching.load_haptic_file(missing)
    stderr = cli("play", missing, "--glove", "none", check=False).stderr
    assert str(caught.value) and str(caught.value) in stderr, (str(caught.value), stderr)
    with pytest.raises(vtouching.Error, match="expected .hjif, .ahap, .haptic or .wav"):
        vtouching.load_haptic_file(os.path.join(out_dir, "clip.mp3"))


def test_stats_agree_with_the_cli():
    mine = {row["name"]: row for row in vtouching.stats(DATASET)}
    theirs = json.loads(cli("stats", DATASET, "--json").stdout)
    rows = theirs if isinstance(theirs, list) else theirs.get("objects", theirs.get("rows"))
    assert rows and len(rows) == len(mine)
    for row in rows:
        name = row["name"]
        for key, value in row.items():
            if isinstance(value, (int, float)) and key in ("v_scale", "v_mean", "v_std", "count"):
                assert mine[name][{"v_scale": "scale", "v_mean": "mean", "v_std": "std"}.get(key, key)] == pytest.approx(value, rel=1e-6, abs=1e-9)


def test_acquire_agrees_with_the_cli(out_dir):
    scan = os.path.join(SOURCE, "tests", "acquisition", "data", "golden_scan")
    result = vtouching.acquire(scan, jobs=1)
    assert result["map"].ndim == 2 and result["map"].dtype == np.float32
    assert result["map"].shape == result["photo"].shape[:2]
    assert 0.0 <= result["map"].min() and result["map"].max() <= 1.0
    cli("acquire", scan, "--out", os.path.join(out_dir, "cli"), "--jobs", "1", "--quiet", "--force")
    name = vtouching.dataset_objects(os.path.join(out_dir, "cli"))[0]
    written = vtouching.open_dataset(os.path.join(out_dir, "cli"), name)["map"]
    assert written.shape == result["map"].shape
    # The PNG holds the normalised map in 16 bits (or 8): equal within its quantisation.
    assert np.abs(written - result["map"]).max() < 1 / 255 + 1e-6
    cli_stats = {r["name"]: r for r in vtouching.stats(os.path.join(out_dir, "cli"))}
    assert cli_stats[name]["scale"] == pytest.approx(result["stats"]["scale"], rel=1e-6)


@pytest.fixture(scope="module")
def slide(tmp_path_factory):
    out = str(tmp_path_factory.mktemp("slide"))
    cli("render", "--trajectory", os.path.join(SOURCE, "assets", "trajectories", "slide.csv"), "--fps", "0",
        "--quiet", "--out", out)
    return os.path.join(out, "traces.csv")


def test_sample_path_is_the_haptic_loops_lookup(slide):
    traces = vtouching.read_traces(slide)
    compared = 0
    for columns in traces.values():
        for name in set(columns["material"][columns["contact"] == 1]):
            if name not in vtouching.dataset_objects(DATASET):
                continue
            rows = (columns["contact"] == 1) & (columns["material"] == name)
            uv = np.stack([columns["u"][rows], columns["v"][rows]], axis=1)
            values = vtouching.sample_path(vtouching.open_dataset(DATASET, name)["map"], uv)
            # traces.csv prints u, v and the value to 5 decimals.
            assert np.abs(values - columns["map_value"][rows]).max() < 2e-3, name
            compared += len(values)
    assert compared > 100
    intensity, frequency, wave = vtouching.render_path(np.full((4, 4), 0.5, np.float32), uv[:50], depth_m=0.0, gain=1.0)
    assert intensity[-1] == pytest.approx(0.5, abs=1e-3)  # the paper's formula at depth 0, after the ramp
    assert wave.shape == (50 * 8,)


def test_recordings_read_into_numpy(out_dir):
    tap = os.path.join(out_dir, "tap-index.haptic")
    with open(tap, "w") as f:
        f.write(TAP)
    csv, wav = os.path.join(out_dir, "rec.csv"), os.path.join(out_dir, "rec.wav")
    cli("play", tap, "--glove", "none", "--record-csv", csv, "--record-wav", wav)
    clip = vtouching.load_recording(csv, wav)
    assert [c["actuator"] for c in clip["channels"]] == ["index"]
    index = clip["channels"][0]
    assert index["pcm"].dtype == np.float32 and len(index["pcm"]) == pytest.approx(clip["duration_s"] * 8000, abs=16)
    assert index["envelope"][:, 1].max() == pytest.approx(0.8, abs=0.01)


def test_codec_round_trip():
    t = np.arange(8000 * 2) / 8000.0
    wave = np.stack([0.5 * np.sin(2 * np.pi * 250 * t), 0.3 * np.sin(2 * np.pi * 120 * t)], axis=1).astype(np.float32)
    pcm = vtouching.decode(vtouching.encode(wave, codec="pcm16"), channels=2, codec="pcm16")
    assert np.abs(pcm[:len(wave)] - wave).max() <= 1 / 32767 + 1e-6
    packets = vtouching.encode(wave, quality=80, block_ms=16)
    back = vtouching.decode(packets, channels=2, quality=80, block_ms=16)[:len(wave)]
    snr = 10 * np.log10(np.sum(wave ** 2) / np.sum((back - wave) ** 2))
    assert snr > 10
    assert sum(len(p) for p in packets) < wave.size * 2  # smaller than 16-bit PCM
    with pytest.raises(vtouching.Error, match="unknown codec"):
        vtouching.encode(wave, codec="mp3")


def test_haptic_files_agree_with_convert(out_dir):
    tap = os.path.join(out_dir, "tap-index.haptic")
    with open(tap, "w") as f:
        f.write(TAP)
    clip = vtouching.load_haptic_file(tap)
    for ext in (".hjif", ".ahap", ".wav"):
        mine = vtouching.save_haptic_file(clip, os.path.join(out_dir, "mine-index" + ext), force=True)
        cli("convert", tap, "--out", os.path.join(out_dir, "cli-index" + ext), "--force")
        with open(mine[0], "rb") as a, open(os.path.join(out_dir, "cli-index" + ext), "rb") as b:
            assert a.read() == b.read(), ext
        back = vtouching.load_haptic_file(mine[0])
        assert back["duration_s"] == pytest.approx(clip["duration_s"], abs=1e-3)
    assert any("synthesised sine" in loss for loss in vtouching.conversion_losses(clip, ".wav"))


def test_fig5_draws_the_paper_figure_from_a_recording(slide, out_dir):
    png = os.path.join(out_dir, "fig5.png")
    p = subprocess.run([sys.executable, os.path.join(SOURCE, "examples", "fig5.py"), slide, "--dataset", DATASET,
                        "--out", png], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                       env=dict(os.environ, MPLBACKEND="Agg"))
    assert p.returncode == 0, p.stderr
    assert "wrote" in p.stdout
    import matplotlib.image
    image = matplotlib.image.imread(png)
    assert image.shape[0] > 300 and image.shape[1] > 800
    # Not blank: the photo and the curves give many distinct colours.
    assert len(np.unique(image.reshape(-1, image.shape[2])[:, :3], axis=0)) > 100
