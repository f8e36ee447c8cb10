"""scripts/render_validation.py renders docs/validation.md from the figures the validation tests
write: a passing, a failing and a known-failure figure come out as such, grouped by case, with the
tolerance and its source; a malformed figure file is refused with its path and line."""

import json
import subprocess
import sys
import unittest

import clitest


def figure(**fields):
    base = {"test": "Suite.Test", "case": "Case A", "reference": "Ref (2000)", "metric": "m", "measured": 1.05,
            "reference_value": 1.0, "tolerance": 0.1, "relative": True, "bound": "within",
            "tolerance_source": "scatter", "pass": True, "known_failure": False,
            "measured_at": "2026-12-02T10:00:00Z"}
    base.update(fields)
    return json.dumps(base)


class RenderValidation(unittest.TestCase):
    def render(self, files):
        folder = clitest.out_dir("figures")
        folder.mkdir()
        for name, lines in files.items():
            (folder / name).write_text("\n".join(lines) + "\n")
        output = clitest.WORK_DIR / "validation.md"
        result = subprocess.run([sys.executable, str(clitest.SOURCE_DIR / "scripts" / "render_validation.py"),
                                 "--figures", str(folder), "--output", str(output)], capture_output=True, text=True)
        return result, (output.read_text() if output.exists() else "")

    def test_rows_results_and_counts(self):
        result, text = self.render({
            "Suite.Test.jsonl": [figure(), figure(metric="bad", measured=2.0, **{"pass": False})],
            "Suite.OtherKnownFailure.jsonl": [figure(test="Suite.OtherKnownFailure", case="Case B",
                                                     metric="runout", measured=9.1, reference_value=29.0,
                                                     tolerance=0.25, known_failure=True, **{"pass": False})],
            "Suite.Limit.jsonl": [figure(test="Suite.Limit", metric="lost", measured=0.0, reference_value=0.0,
                                         bound="at_most", relative=False, tolerance=0.0)],
        })
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("4 figures from 3 tests, measured 2026-12-02 to 2026-12-02: 2 pass, 1 fail, 1 known failure.",
                      text)
        self.assertLess(text.index("## Case A"), text.index("## Case B"))
        self.assertIn("| m | Ref (2000) | 1 | ±10% | scatter | 1.05 (+5.0%) | pass | `Suite.Test` (2026-12-02) |", text)
        self.assertIn("| bad | Ref (2000) | 1 | ±10% | scatter | 2 (+100.0%) | **FAIL** |", text)
        self.assertIn("| runout | Ref (2000) | 29 | ±25% | scatter | 9.1 (-68.6%) | known failure |", text)
        self.assertIn("| lost | Ref (2000) | ≤ 0 | limit | scatter | 0 | pass |", text)

    def test_malformed_file_is_named(self):
        result, _ = self.render({"Suite.Broken.jsonl": [figure(), "{not json"]})
        self.assertNotEqual(result.returncode, 0)
        self.assertIn("Suite.Broken.jsonl:2:", result.stderr)

    def test_no_figures_is_an_error(self):
        result, _ = self.render({})
        self.assertNotEqual(result.returncode, 0)
        self.assertIn("no figures", result.stderr)


if __name__ == "__main__":
    clitest.main()
