"""V-Touching from Python: vibration maps, acquisition and statistics, sampling a map along a path
with the haptic loop's own code, actuator recordings and traces, the tactile codec, and the haptic
files (HJIF, AHAP, Meta .haptic, WAV). Errors raise vtouching.Error with the CLI's message."""
import csv as _csv
import os as _os

import numpy as _np

from ._vtouching import (Error, acquire, conversion_losses, decode, encode, load_haptic_file, load_image, load_map,
                         load_recording, render_path, sample_path, save_haptic_file, stats)

__all__ = ["Error", "acquire", "conversion_losses", "dataset_objects", "decode", "encode", "load_haptic_file",
           "load_image", "load_map", "load_recording", "open_dataset", "read_traces", "render_path", "sample_path",
           "save_haptic_file", "stats"]


def dataset_objects(dataset_dir):
    """Names of the objects of a dataset folder (NAME/NAME_acc.png), sorted."""
    if not _os.path.isdir(dataset_dir):
        raise Error(f"dataset '{dataset_dir}': not a folder")
    return sorted(n for n in _os.listdir(dataset_dir)
                  if _os.path.isfile(_os.path.join(dataset_dir, n, n + "_acc.png")))


def open_dataset(dataset_dir, name):
    """One object of a dataset: {"map": float32 (H, W) 0..1, "photo": uint8 (H, W, 4)}."""
    folder = _os.path.join(dataset_dir, name)
    return {"map": load_map(_os.path.join(folder, name + "_acc.png")),
            "photo": load_image(_os.path.join(folder, name + ".png"))}


def read_traces(path):
    """traces.csv of `vtouching render --trajectory` as numpy columns, one dict per finger:
    {finger: {"time_s", "u", "v", "depth_m", "map_value", "intensity", "contact", "material", ...}}."""
    rows = {}
    with open(path, newline="") as f:
        reader = _csv.DictReader(f)
        if not reader.fieldnames or "finger" not in reader.fieldnames or "time_s" not in reader.fieldnames:
            raise Error(f"traces '{path}': line 1: expected the header of traces.csv (time_s,finger,...)")
        for line, row in enumerate(reader, start=2):
            rows.setdefault(row["finger"], []).append((line, row))
    out = {}
    for finger, lines in rows.items():
        columns = {}
        for key in reader.fieldnames:
            if key == "finger":
                continue
            values = [r[key] for _, r in lines]
            try:
                columns[key] = _np.array(values, dtype=float)
            except ValueError:
                columns[key] = _np.array(values)
        out[finger] = columns
    return out
