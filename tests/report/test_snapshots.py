"""The report's pictures of the scenes: a snapshot*.png that `cdbench snapshot` wrote into an environment's
result folder opens that environment's section, captioned from the JSON beside it, and pack-results keeps it."""

import json
import shutil
import subprocess
import tempfile
import unittest
from pathlib import Path

from PIL import Image

import test_report as fixtures

# What `cdbench snapshot --strategy ours` writes beside its picture, cut to what the report reads.
SIDECAR = {"config": "configs/env1.yaml", "environment": "env1", "frame": 46, "object_count": 52,
           "replay": "RUN/cpu/env1/recordings/o-_r0.poses", "strategy": "ours", "visibility": "cpu",
           "resolution": 800, "view": "iso", "width": 400, "height": 300, "scene_height": 240,
           "colliding_pairs": [[3, 7]], "sets": [{"colour": [31, 119, 180], "members": [3, 7]},
                                                 {"colour": [255, 127, 14], "members": [1, 2]},
                                                 {"colour": [44, 160, 44], "members": [5, 9, 11]}],
           "pcs_size": 7, "objects": []}


def write_snapshot(folder, name="snapshot.png", sidecar=SIDECAR):
    Image.new("RGB", (400, 300), (200, 210, 220)).save(folder / name)
    if sidecar is not None:
        (folder / name).with_suffix(".json").write_text(sidecar if isinstance(sidecar, str) else json.dumps(sidecar))


def section(report, env):
    """The text of one environment's section of REPORT.md."""
    start = report.index(f"\n## {env} (")
    end = report.find("\n## ", start + 1)
    return report[start:end if end >= 0 else len(report)]


class SnapshotsInTheReport(fixtures.InFreshResultDir):

    def test_the_primary_section_opens_with_its_snapshot_and_caption(self):
        fixtures.write_run(self.dir / "cpu" / "env1", "env1", fixtures.backend_rows("cpu", fixtures.CPU_BASE),
                           backend="cpu")
        fixtures.write_run(self.dir / "gl-queries" / "env3", "env3", fixtures.env3_rows(), backend="gl-queries")
        write_snapshot(self.dir / "cpu" / "env1")
        result = fixtures.run_report(self.dir)
        self.assertEqual(result.returncode, 0, result.stderr)
        env1 = section((self.dir / "REPORT.md").read_text(), "env1")
        link = "](cpu/env1/snapshot.png)"
        self.assertIn(link, env1)
        self.assertLess(env1.index(link), env1.index("### Tables"), "the picture heads the section")
        caption = env1[env1.index(link):env1.index("### Tables")]
        for fragment in ("Figure 4.1", "env1 at frame 46, 52 objects", "`o-_r0.poses`", "the 3 potentially colliding "
                         "sets of `ours`", "cpu backend at 800 px", "PCS 7 objects", "1 colliding pair (outlined)"):
            self.assertIn(fragment, caption)
        self.assertNotIn("snapshot", section((self.dir / "REPORT.md").read_text(), "env3"))

    def test_every_snapshot_of_the_folder_in_name_order(self):
        fixtures.write_run(self.dir / "env3", "env3", fixtures.env3_rows())
        write_snapshot(self.dir / "env3", "snapshot-b.png", dict(SIDECAR, environment="env3", frame=9))
        write_snapshot(self.dir / "env3", "snapshot-a.png", dict(SIDECAR, environment="env3", frame=4))
        write_snapshot(self.dir / "env3", "other.png")
        self.assertEqual(fixtures.run_report(self.dir).returncode, 0)
        env3 = section((self.dir / "REPORT.md").read_text(), "env3")
        self.assertLess(env3.index("(env3/snapshot-a.png)"), env3.index("(env3/snapshot-b.png)"))
        self.assertIn("Figure 4.10: env3 at frame 4,", env3)
        self.assertNotIn("other.png", env3)

    def test_a_picture_without_a_readable_json_is_shown_and_says_so(self):
        fixtures.write_run(self.dir / "env1", "env1", fixtures.env1_rows())
        write_snapshot(self.dir / "env1", "snapshot.png", sidecar='{"frame": ')
        write_snapshot(self.dir / "env1", "snapshot-plain.png", sidecar=None)
        result = fixtures.run_report(self.dir)
        self.assertEqual(result.returncode, 0, result.stderr)
        env1 = section((self.dir / "REPORT.md").read_text(), "env1")
        self.assertIn("`snapshot.json` beside it does not read as a snapshot's JSON", env1)
        self.assertIn("`snapshot-plain.png` (no JSON beside it says what it shows)", env1)

    def test_packed_results_keep_the_snapshots(self):
        fixtures.write_run(self.dir / "cpu" / "env1", "env1", fixtures.env1_rows(), backend="cpu")
        write_snapshot(self.dir / "cpu" / "env1")
        packed = self.tmp / "packed"
        result = subprocess.run(["bash", str(fixtures.PACK), str(self.dir), str(packed)], capture_output=True,
                                text=True, timeout=120)
        self.assertEqual(result.returncode, 0, result.stderr)
        for name in ("snapshot.png", "snapshot.json"):
            self.assertEqual((packed / "cpu" / "env1" / name).read_bytes(),
                             (self.dir / "cpu" / "env1" / name).read_bytes(), name)


if __name__ == "__main__":
    unittest.main()
