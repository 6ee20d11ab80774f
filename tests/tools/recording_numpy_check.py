"""The recording format from NumPy's side (docs/recording_format.md): a recording written with
json + numpy alone is read by gearpath (replay --write-recording copies it block for block), and
what gearpath writes is read back by numpy with the same values, shape and per-block metadata.

usage: recording_numpy_check.py GEARPATH_BINARY WORK_DIR
"""
import json
import os
import shutil
import subprocess
import sys

import numpy as np

gearpath, work = sys.argv[1], sys.argv[2]
shutil.rmtree(work, ignore_errors=True)
src = os.path.join(work, "from_numpy")
os.makedirs(src)

n, c, s = 7, 3, 64
rng = np.random.default_rng(7)
samples = rng.standard_normal((n, c, s)).astype("<f4")
np.save(os.path.join(src, "samples.npy"), samples)
manifest = {
    "format": "gearpath-recording", "format_version": 1, "machine_id": "gb-numpy",
    "sample_rate_hz": 12800.0, "samples_per_channel": s,
    "channels": [{"sensor": "A1", "axis": a, "unit": "m/s^2", "sensitivity_mv_per_unit": 100.0}
                 for a in "xyz"],
    "blocks": {"count": n, "sequence": [2**64 - n + i for i in range(n)],
               "t0_ns": [1700000000000000000 + i * 5000000 for i in range(n)],
               "speed_hz": [24.5 + i / 3 for i in range(n)],
               "speed_source": ["acquisition"] * n},
}
with open(os.path.join(src, "manifest.json"), "w") as f:
    json.dump(manifest, f)

out = os.path.join(work, "copied")
subprocess.run([gearpath, "replay", src, "--write-recording", out, "-q"], check=True)

# The reading recipe of the doc.
m = json.load(open(os.path.join(out, "manifest.json")))
got = np.load(os.path.join(out, "samples.npy"))
assert got.dtype == np.float32, got.dtype
assert got.shape == (m["blocks"]["count"], len(m["channels"]), m["samples_per_channel"]), got.shape
assert np.array_equal(got.view(np.uint32), samples.view(np.uint32)), "samples differ"
for key in ("sequence", "t0_ns", "speed_hz", "speed_source"):
    assert m["blocks"][key] == manifest["blocks"][key], key
assert m["machine_id"] == "gb-numpy" and m["sample_rate_hz"] == 12800.0
x = got.transpose(1, 0, 2).reshape(len(m["channels"]), -1)
assert np.array_equal(x[1, s:2 * s], samples[1, 1]), "continuous view"

# Version 2: the same blocks with each one's load, as AccelBlockV2 brought them.
src2 = os.path.join(work, "from_numpy_v2")
os.makedirs(src2)
np.save(os.path.join(src2, "samples.npy"), samples)
manifest_v2 = dict(manifest, format_version=2, load_unit="kN m")
manifest_v2["blocks"] = dict(manifest["blocks"], load=[12.5 + i / 7 for i in range(n)])
with open(os.path.join(src2, "manifest.json"), "w") as f:
    json.dump(manifest_v2, f)
out2 = os.path.join(work, "copied_v2")
subprocess.run([gearpath, "replay", src2, "--write-recording", out2, "-q"], check=True)
m2 = json.load(open(os.path.join(out2, "manifest.json")))
assert m2["format_version"] == 2 and m2["load_unit"] == "kN m", m2
assert m2["blocks"]["load"] == manifest_v2["blocks"]["load"], "loads differ"
print("ok: numpy-written recordings (versions 1 and 2) read by gearpath and back, bit for bit")
