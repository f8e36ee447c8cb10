"""`cascade run` with output.snapshots: PNG frames of the requested size at every output frame, and
fields bit-identical to the same run without snapshots (rendering reads copies of the frames only).
"""

import struct
import unittest

import h5py
import numpy as np

import clitest

SNAPSHOTS = """
output:
  interval: 0.01
  snapshots:
    - {field: pore_pressure, phase: soil, translucent: [water], width: 320, height: 180}
    - {name: phases, phase: all, width: 200, height: 100}
"""


def case_text(with_snapshots):
    text = clitest.case("submerged_layer_2d").read_text()
    start = text.index("output:\n")
    end = text.index("\n\n", start)
    replacement = SNAPSHOTS if with_snapshots else "\noutput:\n  interval: 0.01\n"
    return text[:start] + replacement.lstrip("\n") + text[end:]


def png_size(path):
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", f"{path} is not a PNG"
    return struct.unpack(">II", data[16:24])


def datasets(path):
    out = {}
    with h5py.File(path, "r") as f:
        f.visititems(lambda name, item: out.__setitem__(name, item[()]) if isinstance(item, h5py.Dataset) else None)
    return out


class Snapshots(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dirs = {}
        for with_snapshots in (False, True):
            name = "with" if with_snapshots else "without"
            case = clitest.WORK_DIR / f"{name}.yaml"
            case.write_text(case_text(with_snapshots))
            out = clitest.out_dir(name)
            result = clitest.run("run", case, "--out", out, "--until", "0.03", "--threads", "1", timeout=120)
            assert result.returncode == 0, result.stderr
            cls.dirs[name] = out

    def test_frames_have_the_requested_size(self):
        snapshots = self.dirs["with"] / "snapshots"
        with h5py.File(self.dirs["with"] / "fields.h5", "r") as f:
            frames = len(f["frames"])
        pore = sorted(snapshots.glob("pore_pressure_*.png"))
        phases = sorted(snapshots.glob("phases_*.png"))
        self.assertEqual([p.name for p in pore], [f"pore_pressure_{k:06d}.png" for k in range(len(pore))])
        self.assertEqual(len(pore), len(phases))
        self.assertGreaterEqual(len(pore), 4)  # t = 0, 0.01, 0.02, 0.03
        self.assertEqual(len(pore), frames)
        for p in pore:
            self.assertEqual(png_size(p), (320, 180))
        for p in phases:
            self.assertEqual(png_size(p), (200, 100))
        self.assertFalse((self.dirs["without"] / "snapshots").exists())

    def test_fields_are_bit_identical(self):
        a = datasets(self.dirs["without"] / "fields.h5")
        b = datasets(self.dirs["with"] / "fields.h5")
        self.assertEqual(sorted(a), sorted(b))
        self.assertGreater(len(a), 5)
        for name in a:
            np.testing.assert_array_equal(a[name], b[name], err_msg=name)
            self.assertEqual(a[name].tobytes(), b[name].tobytes(), name)
        self.assertEqual((self.dirs["without"] / "probes.csv").read_bytes(),
                         (self.dirs["with"] / "probes.csv").read_bytes())


if __name__ == "__main__":
    clitest.main()
