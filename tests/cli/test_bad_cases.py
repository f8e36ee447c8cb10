"""Bad case files, bad --set overrides and bad options: `cascade run` exits 2 before writing anything,
with one line on stderr that names the key (and, for a key in the file, its line).

Each tests/cli/bad_cases/NAME.yaml is cases/hydrostatic_tank_2d.yaml with one defect and the same line
numbers, or, for the soil_* files, cases/infiltration_1d.yaml; BAD_CASES below says what each must report.
A soil_hyetograph_* case may name a CSV file beside it (a hyetograph).
"""

import re

import unittest

import clitest

# file stem: (key as a regex, line in the file or None when the error has no place in it, message regex)
BAD_CASES = {
    "missing_dp": (r"dp", None, r"is missing"),
    "dp_zero": (r"dp", 8, r"must be greater than 0 \(is 0\)"),
    "dp_negative": (r"dp", 8, r"must be greater than 0 \(is -0\.02\)"),
    "dp_not_number": (r"dp", 8, r"expected a number, got 'fine'"),
    "unknown_top_key": (r"end_tme", 11, r"unknown key"),
    "unknown_nested_key": (r"bodies\[1\]\.colour", 32, r"unknown key"),
    "gravity_length": (r"gravity", 17, r"has 3 components.*needs 2"),
    "box_min_length": (r"bodies\[1\]\.shape\.box\.min", 33, r"has 1 component.*needs 2"),
    "dimensions_4": (r"dimensions", 7, r"must be 2 or 3 \(is 4\)"),
    "end_time_negative": (r"end_time", 10, r"must be greater than 0"),
    "h_over_dp_range": (r"h_over_dp", 9, r"must be in \[1, 3\] \(is 5\)"),
    "domain_min_ge_max": (r"domain\.max", 15, r"must be greater than domain\.min on axis z"),
    "undefined_material": (r"bodies\[1\]\.material", 32, r"'mud' is not a material"),
    "duplicate_body": (r"bodies\[1\]\.name", 30, r"'tank' is already the name of bodies\[0\]"),
    "fluid_no_material": (r"bodies\[1\]\.material", 30, r"is missing"),
    "material_no_model": (r"materials\[0\]", 20, r"has no model"),
    "no_fluid_body": (r"bodies", 23, r"has no fluid body"),
    "polygon_two_vertices": (r"bodies\[1\]\.shape\.polygon\.vertices", 33, r"has 2 vertices"),
    "unknown_probe_kind": (r"probes\[1\]\.kind", 42, r"got 'median'"),
    "probe_bad_field": (r"probes\[1\]\.field", 42, r"'temperature' is not a field"),
    "probe_outside": (r"probes\[0\]\.position", 40, r"outside the domain on axis z"),
    "cfl_too_big": (r"numerics\.cfl", 36, r"must be in \(0, 1\] \(is 1\.5"),
    "duplicate_key": (r"dp", 10, r"is given twice \(first at line 8\)"),
    # Issue 14: a Latin-1 byte was accepted here and failed CreateSimulation with an empty message.
    "latin1_comment": (r"\(encoding\)", 12, r"byte 0xE9 is not UTF-8: save the case file as UTF-8"),
    # Issue 14: reported as "key 'dimensions' is missing" (the string ran on to the end of the file).
    "unterminated_quote": (r"\(yaml\)", 5, r"a quote opened on this line is not closed on it"),
    # yaml-cpp reports an unclosed flow sequence where it gives up looking for the `]`, not where the
    # `[` is (line 17): accept the lines up to that point.
    "malformed_yaml": (r"\(yaml\)", range(17, 20), r"end of sequence flow not found"),
    # The tank walls reach x = -0.12, the domain starts at -0.05: the loader's check of the shape
    # against the domain reports it before the particle builder could.
    "wall_outside_domain": (r"bodies\[0\]\.shape\.box\.min", 27, r"outside the domain on axis x"),
    # Errors of the particle builder: they name the key but carry no line.
    "empty_fluid": (r"bodies\[1\]", None, r"body 'water' has no particles"),
    "no_sound_speed": (r"materials\[0\]\.water\.sound_speed", None, r"no sound speed"),
    # Soil materials, soil bodies and hydraulics (copies of cases/infiltration_1d.yaml).
    "soil_conductivity_zero": (r"materials\[0\]\.soil\.saturated_conductivity", 29, r"must be greater than 0 \(is 0\)"),
    "soil_porosity_one": (r"materials\[0\]\.soil\.porosity", 28, r"must be in \(0, 1\) \(is 1\)"),
    "soil_s_min_above_s_max": (r"materials\[0\]\.soil\.hydraulic\.gardner\.s_min", 43,
                               r"s_min must be less than s_max \(got s_min 0\.8, s_max 0\.5\)"),
    "soil_friction_angle_90": (r"materials\[0\]\.soil\.mechanical\.drucker_prager\.friction_angle", 41,
                               r"must be in \[0, 90\) degrees \(is 90\)"),
    "soil_unknown_hydraulic_model": (r"materials\[0\]\.soil\.hydraulic\.brooks_corey", 43,
                                     r"unknown key \(known here: van_genuchten, gardner, liakopoulos\)"),
    "soil_drying_above_ponding": (r"hydraulics\.drying_pressure", 62, r"must be below ponding_pressure"),
    "soil_probe_phase_water": (r"probes\[0\]\.phase", 69, r"'pore_pressure' is a field of soil particles"),
    # Units: "<number> <unit>" where the schema names the field's SI unit (docs/cases.md, "Units").
    "units_wrong_dimension": (r"dp", 8, r"takes a length \(m\); 'kPa' is a pressure"),
    "units_unknown": (r"end_time", 10, r"unknown unit 'fortnight' \(units of a time: s, min, h, day, d\)"),
    "units_on_plain_number": (r"h_over_dp", 9, r"takes a plain number without a unit, got '1\.3 m'"),
    "units_malformed": (r"dp", 8, r"expected a number, got '2cm' \(or a number and a unit of a length: m, cm, mm, km\)"),
    # Hyetographs: errors in the CSV name the key at its line in the case, and the CSV file and row.
    "soil_hyetograph_negative_intensity": (r"hydraulics\.hyetograph\.file", 61,
                                           r"/soil_hyetograph_negative_intensity\.csv:4: the intensity must not be "
                                           r"negative \(is -5\)"),
    "soil_hyetograph_missing_file": (r"hydraulics\.hyetograph\.file", 61,
                                     r"cannot read the hyetograph .*/bad_cases/no_such_storm\.csv"),
    "soil_hyetograph_time_unit": (r"hydraulics\.hyetograph\.time_unit", 61, r"takes a time \(s\); 'mm' is a length"),
    "soil_hyetograph_with_rainfall": (r"hydraulics\.hyetograph", 62,
                                      r"cannot be given together with rainfall_intensity or rainfall"),
    # The particle builder knows the body's extent: p_w = ρ g (z_wt - z) < -K_w at the top.
    "soil_water_table_too_deep": (r"bodies\[1\]\.initial\.water_table", None, r"at or below -K_w = -200000"),
}

BASE = "hydrostatic_tank_2d"


class BadCaseFiles(unittest.TestCase):
    def test_every_file_has_an_expectation(self):
        files = {p.stem for p in (clitest.SOURCE_DIR / "tests/cli/bad_cases").glob("*.yaml")}
        self.assertEqual(files, set(BAD_CASES))
        self.assertGreaterEqual(len(files), 18)

    def test_bad_case_files(self):
        for name, (key, line, message) in sorted(BAD_CASES.items()):
            with self.subTest(case=name):
                path = clitest.SOURCE_DIR / "tests/cli/bad_cases" / f"{name}.yaml"
                out = clitest.out_dir(f"bad_{name}")
                # --until keeps a case that wrongly loads from running for long.
                p = clitest.run("run", path, "--out", out, "--until", "0.001")
                self.assertEqual(p.returncode, 2, p.stderr)
                lines = p.stderr.strip().splitlines()
                self.assertEqual(len(lines), 1, p.stderr)
                where = re.escape(str(path)) + (r":(\d+):\d+" if line is not None else "")
                m = re.fullmatch(rf"cascade run: {where}: key '{key}': (.*)", lines[0])
                self.assertIsNotNone(m, f"stderr {lines[0]!r} does not name file{'/line' if line else ''} and key "
                                        f"{key!r}")
                if line is not None:
                    expected = line if isinstance(line, range) else [line]
                    self.assertIn(int(m.group(1)), expected, lines[0])
                self.assertRegex(m.group(m.lastindex), message)
                self.assertFalse(out.exists(), "a case error must not create the output folder")
                self.assertEqual(p.stdout, "")

    def test_create_loads_the_case_on_the_client(self):
        # `cascade create` reads the case (and its hyetograph) here and sends the spec: a bad case is
        # reported as by `cascade run`, before any server is asked (none listens at port 1).
        for name in ("units_unknown", "soil_hyetograph_negative_intensity"):
            with self.subTest(case=name):
                key, line, message = BAD_CASES[name]
                path = clitest.SOURCE_DIR / "tests/cli/bad_cases" / f"{name}.yaml"
                p = clitest.run("create", path, "--server", "127.0.0.1:1")
                self.assertEqual(p.returncode, 2, p.stderr)
                self.assertRegex(p.stderr.strip(), rf"^cascade create: {re.escape(str(path))}:{line}:\d+: key '{key}': "
                                                   rf".*{message}$")

    def test_missing_case_file(self):
        out = clitest.out_dir("bad_missing_file")
        missing = clitest.WORK_DIR / "no_such_case.yaml"
        p = clitest.run("run", missing, "--out", out)
        self.assertEqual(p.returncode, 2, p.stderr)
        self.assertRegex(p.stderr, rf"^cascade run: {re.escape(str(missing))}: key '\(file\)': cannot open")
        self.assertFalse(out.exists())


class BadOverridesAndOptions(unittest.TestCase):
    # (arguments after the case file, stderr regex)
    SET_ERRORS = {
        "unknown_key": (["--set", "dpp=0.02"], r"key 'dpp': unknown key 'dpp' .*\(from --set dpp=0\.02\)"),
        "unknown_nested": (["--set", "bodies[1].colour=blue"], r"key 'bodies\[1\]\.colour': unknown key"),
        "index_out_of_range": (["--set", "bodies[5].name=x"], r"key 'bodies\[5\]\.name': .*none at \[5\]"),
        "bad_value": (["--set", "dp=abc"], r"key 'dp': expected a number, got 'abc' \(or a number and a unit of a "
                                           r"length: m, cm, mm, km\) \(from --set dp=abc\)"),
        "invalid_value": (["--set", "dp=-1"], r"key 'dp': must be greater than 0 \(is -1\) \(from --set dp=-1\)"),
        "no_equals": (["--set", "dp"], r"key '--set': 'dp' is not of the form"),
        "bad_yaml": (["--set", "gravity=[0, -9.81"], r"key '--set': the value of .* is not valid YAML"),
        # Issue 14: these intervals froze `cascade run` and every request of the server.
        "output_interval_tiny": (["--set", "output.interval=1e-300"],
                                 r"key 'output\.interval': must be 0 \(end_time / 100\) or at least 1e-6 s "
                                 r"\(is 1e-300 s\)"),
        "probe_interval_tiny": (["--set", "output.probe_interval=1e-20"],
                                r"key 'output\.probe_interval': must be 0 .* or at least 1e-6 s"),
        # Issue 14: values that describe nothing real (server/scenario/plausible_ranges.h).
        "water_density_huge": (["--set", "materials[0].water.density=1e300"],
                               r"key 'materials\[0\]\.water\.density': must be in \[100, 20000\] kg/m\^3 "
                               r"\(is 1e\+300\): liquids lie between"),
        "sound_speed_tiny": (["--set", "materials[0].water.sound_speed=1e-10"],
                             r"key 'materials\[0\]\.water\.sound_speed': must be in \[0\.1, 10000\] m/s"),
    }
    # The same on a soil case (cases/infiltration_1d.yaml).
    SOIL_SET_ERRORS = {
        "conductivity_huge": (["--set", "materials[0].soil.saturated_conductivity=1e6"],
                              r"key 'materials\[0\]\.soil\.saturated_conductivity': must be in \[1e-15, 10\] m/s "
                              r"\(is 1000000\)"),
        "grain_density_huge": (["--set", "materials[0].soil.grain_density=1e300"],
                               r"key 'materials\[0\]\.soil\.grain_density': must be in \[300, 10000000\]"),
        "youngs_modulus_tiny": (["--set", "materials[0].soil.rigid=false",
                                 "--set", "materials[0].soil.mechanical={linear_elastic: {youngs_modulus: 1e-30, "
                                 "poisson_ratio: 0.3}}"],
                                r"key 'materials\[0\]\.soil\.mechanical\.linear_elastic\.youngs_modulus': must be in "
                                r"\[100, 1e\+12\] Pa"),
        "rain_huge": (["--set", "hydraulics.rainfall_intensity=1e10"],
                      r"key 'hydraulics\.rainfall_intensity': must be in \[-1, 1\] m/s \(is 1e\+10\)"),
    }
    OPTION_ERRORS = {
        "threads_0": (["--threads", "0"], r"--threads must be a whole number from 1 to 1024"),
        "threads_word": (["--threads", "two"], r"--threads needs a number, got 'two'"),
        "threads_no_value": (["--threads"], r"--threads needs a value"),
        "until_negative": (["--until", "-1"], r"--until must be a positive time"),
        "precision": (["--precision", "half"], r"--precision must be float or double, not 'half'"),
        "unknown_option": (["--bogus"], r"unknown option '--bogus'"),
        "two_cases": (["other.yaml"], r"unexpected argument 'other\.yaml'"),
    }

    def check(self, name, args, pattern, with_out=True, base=BASE):
        out = clitest.out_dir(f"opt_{name}")
        argv = ["run", clitest.case(base), "--until", "0.001"] + (["--out", out] if with_out else []) + args
        p = clitest.run(*argv)
        self.assertEqual(p.returncode, 2, p.stderr)
        self.assertRegex(p.stderr, rf"^cascade run: .*{pattern}")
        self.assertEqual(len(p.stderr.strip().splitlines()), 1, p.stderr)
        self.assertFalse(out.exists(), "an argument error must not create the output folder")

    def test_bad_set(self):
        for name, (args, pattern) in sorted(self.SET_ERRORS.items()):
            with self.subTest(set=name):
                self.check(f"set_{name}", args, pattern)

    def test_bad_soil_set(self):
        for name, (args, pattern) in sorted(self.SOIL_SET_ERRORS.items()):
            with self.subTest(set=name):
                self.check(f"soil_set_{name}", args, pattern, base="infiltration_1d")

    def test_bad_options(self):
        for name, (args, pattern) in sorted(self.OPTION_ERRORS.items()):
            with self.subTest(option=name):
                self.check(name, args, pattern)

    def test_missing_out(self):
        self.check("missing_out", [], r"--out DIR is required", with_out=False)

    def test_missing_case(self):
        out = clitest.out_dir("opt_missing_case")
        p = clitest.run("run", "--out", out)
        self.assertEqual(p.returncode, 2, p.stderr)
        self.assertIn("no case file given", p.stderr)
        self.assertFalse(out.exists())

    def test_commands(self):
        p = clitest.run()
        self.assertEqual(p.returncode, 2)
        self.assertIn("usage: cascade", p.stderr)
        p = clitest.run("frobnicate")
        self.assertEqual(p.returncode, 2)
        self.assertIn("unknown command 'frobnicate'", p.stderr)
        p = clitest.run("help")
        self.assertEqual(p.returncode, 0)
        self.assertIn("run CASE.yaml --out DIR", p.stdout)


class BadJournals(unittest.TestCase):
    """`cascade run --replay` refuses, before the first step, a journal of another case and forcing
    that UpdateForcing would refuse (issue 14: both were applied)."""

    CREATE = '{"caller":"local","command":"create","case_name":"%s"}'
    RAIN = ('{"step":"3","time":6,"caller":"local","command":"update_forcing","update_mask":["rainfall.intensity"],'
            '"old_forcing":{"rainfall":{"intensity":1e-06},"ponding":{}},"new_forcing":{"rainfall":{"intensity":%s},'
            '"ponding":{}}}')
    PONDING = ('{"step":"3","time":6,"caller":"local","command":"update_forcing","update_mask":["ponding.p_max"],'
               '"old_forcing":{"rainfall":{"intensity":1e-06},"ponding":{}},"new_forcing":{"rainfall":{"intensity":1e-06},'
               '"ponding":{"p_max":%s}}}')
    JOURNALS = {
        "other_case": ([CREATE % "hydrostatic_tank_2d"], r"step 0: the journal is of case 'hydrostatic_tank_2d', "
                                                         r"not 'rain_column'"),
        "nan_rain": ([CREATE % "rain_column", RAIN % '"NaN"'],
                     r"step 3: rainfall\.intensity must be in \[-1, 1\] m/s \(is nan\)"),
        "huge_rain": ([CREATE % "rain_column", RAIN % "1e10"],
                      r"step 3: rainfall\.intensity must be in \[-1, 1\] m/s \(is 1e\+10\)"),
        "nan_ponding": ([CREATE % "rain_column", PONDING % '"NaN"'],
                        r"step 3: ponding\.p_max must be in \[-100000000, 100000000\] Pa \(is nan\)"),
    }

    def test_refused_before_the_first_step(self):
        for name, (lines, pattern) in sorted(self.JOURNALS.items()):
            with self.subTest(journal=name):
                out = clitest.out_dir(f"journal_{name}")
                out.mkdir(parents=True, exist_ok=True)
                journal = out / "journal.jsonl"
                journal.write_text("\n".join(lines) + "\n")
                p = clitest.run("run", clitest.fixture("rain_column"), "--out", out / "run", "--replay", journal)
                self.assertEqual(p.returncode, 1, p.stderr)
                self.assertRegex(p.stderr, rf"cascade run: failed: journal\.jsonl, {pattern}")
                self.assertIn('"steps": 0', (out / "run" / "run.json").read_text())


if __name__ == "__main__":
    clitest.main()
