"""scripts/check_docs.py: README.md and docs/ hold only links that resolve, source paths that exist and
`cdbench` commands the CLI accepts; and the check fails on a broken link, a missing anchor, a source
file that is not there, an unknown subcommand or option."""

import os
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
CHECK = ROOT / "scripts" / "check_docs.py"
BINARY = os.environ.get("CDBENCH_BINARY", str(ROOT / "build" / "cdbench"))


def run_check(*pages):
    return subprocess.run([sys.executable, str(CHECK), "--cdbench", BINARY, *map(str, pages)],
                          capture_output=True, text=True, timeout=120)


@unittest.skipUnless(os.access(BINARY, os.X_OK), f"no cdbench binary at {BINARY}")
class CheckDocsTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = Path(self.tmp.name)
        (self.dir / "other.md").write_text("# Other page\n\n## Running a sweep\n\ntext\n")
        (self.dir / "picture.png").write_bytes(b"\x89PNG")

    def tearDown(self):
        self.tmp.cleanup()

    def page(self, body):
        path = self.dir / "page.md"
        path.write_text("# A page\n\n" + body + "\n")
        return path

    def test_the_projects_readme_and_docs_pass(self):
        done = run_check()
        self.assertEqual(done.returncode, 0, done.stdout + done.stderr)
        # It read the pages and found commands to check, not nothing.
        self.assertRegex(done.stderr, r"[1-9]\d* links, [1-9]\d* source paths, [1-9]\d* cdbench commands")

    def test_good_links_and_commands_pass(self):
        page = self.page("See [the other page](other.md#running-a-sweep), ![a picture](picture.png),\n"
                         "[this page](#a-page) and [the web](https://example.org/x.md).\n\n"
                         "```bash\nbuild/cdbench run configs/env3.yaml --objects 50 \\\n"
                         "  --resolutions 256 --out /tmp/x | tail -3\n```\n\n"
                         "Inline: `cdbench check --update-baseline`, `cdbench snapshot --help`; "
                         "the header text `cdbench scenario v2` is prose.")
        done = run_check(page)
        self.assertEqual(done.returncode, 0, done.stdout + done.stderr)
        self.assertIn("3 cdbench commands", done.stderr)

    def test_a_broken_link_fails_naming_file_and_line(self):
        page = self.page("Fine line.\n\nSee [the guide](no-such-guide.md).")
        done = run_check(page)
        self.assertEqual(done.returncode, 1)
        self.assertIn("page.md:5: link 'no-such-guide.md'", done.stdout)

    def test_a_missing_picture_fails(self):
        done = run_check(self.page('<img src="gone.gif" width="400">'))
        self.assertEqual(done.returncode, 1)
        self.assertIn("gone.gif", done.stdout)

    def test_a_missing_anchor_fails(self):
        done = run_check(self.page("[sweeps](other.md#sweeps-and-shards)"))
        self.assertEqual(done.returncode, 1)
        self.assertIn("has no heading with id #sweeps-and-shards", done.stdout)

    def test_an_option_the_cli_does_not_have_fails(self):
        page = self.page("```bash\nbuild/cdbench run configs/env1.yaml --objects 50 \\\n  --no-such-option 3\n```")
        done = run_check(page)
        self.assertEqual(done.returncode, 1)
        self.assertIn("page.md:4: `cdbench run --no-such-option`: run has no option --no-such-option", done.stdout)

    def test_an_option_of_another_subcommand_fails(self):
        # --update-baseline is check's, not run's.
        done = run_check(self.page("Then `cdbench run configs/env1.yaml --update-baseline`."))
        self.assertEqual(done.returncode, 1)
        self.assertIn("run has no option --update-baseline", done.stdout)

    def test_a_source_file_that_moved_fails(self):
        done = run_check(self.page("The tables are written by harness/TableWriters.cpp and\n"
                                   "`scripts/reproduce.sh` runs them."))
        self.assertEqual(done.returncode, 1)
        self.assertIn("page.md:3: harness/TableWriters.cpp does not exist", done.stdout)
        self.assertNotIn("reproduce.sh", done.stdout)

    def test_a_subcommand_the_cli_does_not_have_fails(self):
        done = run_check(self.page("```\ncdbench sweep configs/env1.yaml\n```\n\nand `cdbench chekc`"))
        self.assertEqual(done.returncode, 1)
        self.assertIn("no subcommand 'sweep'", done.stdout)
        self.assertIn("no subcommand 'chekc'", done.stdout)

    def test_no_binary_is_bad_usage(self):
        done = subprocess.run([sys.executable, str(CHECK), "--cdbench", str(self.dir / "nothing")],
                              capture_output=True, text=True, timeout=60)
        self.assertEqual(done.returncode, 2)
        self.assertIn("not an executable cdbench", done.stderr)


if __name__ == "__main__":
    unittest.main()
