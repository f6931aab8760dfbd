"""The Python API on a small config given as a dict (generic plugins only) and on the shipped
robust config: ports, step against run, dict against file, errors with their paths.

Run by ctest (python_api) as: python3 test_api.py SOURCE_DIR, with the module on PYTHONPATH."""

import json
import math
import os
import sys
import tempfile
import threading
import unittest
import warnings

import numpy

import ftsense

SOURCE = sys.argv.pop(1) if __name__ == "__main__" else os.environ["FTSENSE_SOURCE_DIR"]
SEED = 20261123  # fixed; printed by main()


def small_config():
    return {
        "sample_period_s": 0.001,
        "inputs": {
            "measured": {"columns": ["cell/c1/force_N", "cell/c2/force_N", "cell/c3/force_N"], "unit": "N"},
            "reference": {"columns": ["model/c1/force_N", "model/c2/force_N", "model/c3/force_N"], "unit": "N"},
        },
        "stages": [
            {"name": "residual", "plugin": "difference_residual",
             "inputs": {"measured": "input.measured", "virtual": "input.reference"}},
            {"name": "smooth", "plugin": "low_pass", "params": {"cutoff_hz": 2.0},
             "inputs": {"signal": "residual.residual"}},
            {"name": "detect", "plugin": "threshold_detector", "params": {"thresholds": [5.0]},
             "inputs": {"signal": "smooth.filtered"}},
        ],
        "monitor": {
            "channels": ["c1", "c2", "c3"],
            "measured": "input.measured", "virtual": "input.reference",
            "fault_estimate": "smooth.filtered", "recovered": "input.reference",
            "fault": "detect.fault", "fault_type": "detect.fault_type",
        },
    }


def small_inputs(ticks=3000):
    """Three cells reading a reference plus noise; cell c2 gains a 20 N offset at t = 1.5 s."""
    rng = numpy.random.default_rng(SEED)
    reference = 100.0 + 10.0 * rng.standard_normal((ticks, 3))
    measured = reference + rng.standard_normal((ticks, 3))
    measured[ticks // 2:, 1] += 20.0
    return {"measured": measured, "reference": reference}


def same(a, b):
    """Bitwise equal arrays (NaN equal to NaN)."""
    a = numpy.asarray(a)
    b = numpy.asarray(b)
    return a.shape == b.shape and a.tobytes() == b.tobytes()


class SmallDictConfig(unittest.TestCase):
    def setUp(self):
        self.p = ftsense.Pipeline(small_config())

    def test_ports(self):
        self.assertEqual([(i.name, i.dim, i.unit) for i in self.p.inputs], [("measured", 3, "N"), ("reference", 3, "N")])
        self.assertEqual(self.p.inputs[0].columns, ["cell/c1/force_N", "cell/c2/force_N", "cell/c3/force_N"])
        outputs = {o.name: o for o in self.p.outputs}
        self.assertEqual(outputs["residual.residual"].dim, 3)
        self.assertEqual(outputs["residual.residual"].unit, "N")
        self.assertEqual(outputs["smooth.filtered"].unit, "N")  # a unit-generic output takes its input's unit
        self.assertEqual(outputs["detect.fault"].unit, "1")
        self.assertTrue(outputs["smooth.filtered"].description)
        self.assertEqual(self.p.channels, ["c1", "c2", "c3"])
        self.assertEqual(self.p.columns[:7], ["time_s", "c1/measured_N", "c1/virtual_N", "c1/fault_estimate_N",
                                              "c1/recovered_N", "c1/fault", "c1/fault_type"])
        self.assertEqual(len(self.p.columns), 1 + 3 * 7)
        self.assertEqual(self.p.monitor["fault"], "detect.fault")
        self.assertEqual(self.p.monitor["measured"], "input.measured")
        self.assertEqual(self.p.sample_period_s, 0.001)

    def test_run_flags_the_offset_channel_only(self):
        out = self.p.run(small_inputs())
        fault = out["detect.fault"]
        self.assertEqual(fault.shape, (3000, 3))
        self.assertFalse(fault[:, 0].any())
        self.assertFalse(fault[:, 2].any())
        first = int(numpy.argmax(fault[:, 1] != 0))
        self.assertTrue(fault[first, 1] == 1 and 1500 <= first < 3000, first)

    def test_step_equals_run(self):
        inputs = small_inputs(800)
        whole = self.p.run(inputs)
        self.p.reset()
        for k in range(800):
            tick = self.p.step(k * 0.001, {name: rows[k] for name, rows in inputs.items()})
            for name, rows in whole.items():
                self.assertTrue(same(tick[name], rows[k]), (name, k, tick[name], rows[k]))

    def test_run_table_is_the_monitor_of_run(self):
        inputs = small_inputs(500)
        time = 10.0 + 0.001 * numpy.arange(500)
        table = self.p.run_table(inputs, time=time)
        out = self.p.run(inputs, time=time)
        self.assertEqual(table.columns, self.p.columns)
        self.assertTrue(same(table["time_s"], time))
        self.assertTrue(same(table["c2/measured_N"], inputs["measured"][:, 1]))
        self.assertTrue(same(table["c3/fault_estimate_N"], out["smooth.filtered"][:, 2]))
        self.assertTrue(same(table["c1/fault_type"], out["detect.fault_type"][:, 0]))

    def test_run_resets_unless_told(self):
        inputs = small_inputs(300)
        first = self.p.run(inputs)["smooth.filtered"]
        again = self.p.run(inputs)["smooth.filtered"]
        self.assertTrue(same(first, again))
        carried = self.p.run(inputs, reset=False)["smooth.filtered"]
        self.assertFalse(same(first, carried))

    def test_dict_equals_file(self):
        with tempfile.TemporaryDirectory() as work:
            path = os.path.join(work, "small.json")
            with open(path, "w") as f:
                json.dump(small_config(), f)
            from_file = ftsense.Pipeline(path)
            inputs = small_inputs(1000)
            a = from_file.run(inputs)
            b = self.p.run(inputs)
            self.assertEqual(list(a), list(b))
            for name in a:
                self.assertTrue(same(a[name], b[name]), name)

    def test_thresholds_dict_applied(self):
        calm = ftsense.Pipeline(small_config(), thresholds={"stages": {"detect": {"thresholds": [50.0]}}})
        self.assertFalse(calm.run(small_inputs())["detect.fault"].any())

    def test_bad_inputs_raise(self):
        tick = {name: rows[0] for name, rows in small_inputs(1).items()}
        with self.assertRaisesRegex(KeyError, "missing pipeline input.*reference"):
            self.p.step(0.0, {"measured": tick["measured"]})
        with self.assertRaisesRegex(KeyError, "no pipeline input named 'mesured'.*did you mean 'measured'"):
            self.p.step(0.0, dict(tick, mesured=tick["measured"]))
        with self.assertRaisesRegex(ValueError, r"input 'reference': expected 3 values, got shape \(2,\)"):
            self.p.step(0.0, dict(tick, reference=[1.0, 2.0]))
        inputs = small_inputs(10)
        with self.assertRaisesRegex(ValueError, r"input 'reference': 9 rows, but input 'measured' has 10"):
            self.p.run(dict(inputs, reference=inputs["reference"][:9]))
        with self.assertRaisesRegex(ValueError, r"time: expected 10 values"):
            self.p.run(inputs, time=[0.0, 0.001])
        with self.assertRaisesRegex(KeyError, "no signal named 'smooth.filterd'"):
            self.p.run(inputs, outputs=["smooth.filterd"])


class Threads(unittest.TestCase):
    def test_run_releases_the_gil_and_guards_its_pipeline(self):
        """While one thread runs a long run, another runs Python (the GIL is released) and is
        refused the same pipeline (its buffers are in use) but may step another."""
        p = ftsense.Pipeline(small_config())
        other = ftsense.Pipeline(small_config())
        inputs = small_inputs(400000)
        done = threading.Event()
        worker = threading.Thread(target=lambda: (p.run(inputs, outputs=["detect.fault"]), done.set()))
        refused = stepped = 0
        worker.start()
        while not done.is_set():
            try:
                p.reset()
            except RuntimeError as e:
                self.assertIn("in use by another thread", str(e))
                refused += 1
                other.step(0.0, {name: rows[0] for name, rows in inputs.items()})
                stepped += 1
        worker.join()
        self.assertGreater(refused, 0)
        self.assertEqual(stepped, refused)
        p.reset()  # free again once the run is over


class BadConfigs(unittest.TestCase):
    def test_dict_problem_has_its_json_pointer(self):
        config = small_config()
        config["stages"][1]["params"]["cutoff_hz"] = -2.0
        config["stages"][2]["plugin"] = "threshold_detectr"
        with self.assertRaises(ftsense.ConfigError) as caught:
            ftsense.Pipeline(config)
        paths = [path for path, _ in caught.exception.problems]
        self.assertIn("/stages/1/params/cutoff_hz", paths)
        self.assertIn("/stages/2/plugin", paths)
        self.assertIn("/stages/1/params/cutoff_hz", str(caught.exception))
        self.assertIsInstance(caught.exception, ValueError)
        self.assertIsInstance(caught.exception, ftsense.Error)

    def test_file_problem_has_the_file_and_pointer(self):
        config = small_config()
        config["stages"][1]["params"]["cutoff_hz"] = -2.0
        with tempfile.TemporaryDirectory() as work:
            path = os.path.join(work, "bad.json")
            with open(path, "w") as f:
                json.dump(config, f)
            with self.assertRaises(ftsense.ConfigError) as caught:
                ftsense.Pipeline(path)
            self.assertEqual([p for p, _ in caught.exception.problems], [path + ":/stages/1/params/cutoff_hz"])
            self.assertIn(path + ":/stages/1/params/cutoff_hz", str(caught.exception))

    def test_json_syntax_error_has_line_and_column(self):
        with tempfile.TemporaryDirectory() as work:
            path = os.path.join(work, "broken.json")
            with open(path, "w") as f:
                f.write('{\n  "sample_period_s": 0.001,,\n}\n')
            with self.assertRaisesRegex(ftsense.ConfigError, re_escape(path) + r":2:\d+"):
                ftsense.Pipeline(path)

    def test_missing_files(self):
        with self.assertRaisesRegex(ftsense.UsageError, "no_such_config.json"):
            ftsense.Pipeline(os.path.join(SOURCE, "no_such_config.json"))
        p = ftsense.Pipeline(small_config())
        with self.assertRaisesRegex(ftsense.LogError, "no_such_log.csv"):
            p.run_log(os.path.join(SOURCE, "no_such_log.csv"))

    def test_log_missing_columns_named_with_the_config(self):
        with tempfile.TemporaryDirectory() as work:
            log = os.path.join(work, "log.csv")
            with open(log, "w") as f:
                f.write("time_s,cell/c1/force_N\n0,1\n0.001,1\n")
            with self.assertRaises(ftsense.ConfigError) as caught:
                ftsense.Pipeline(small_config()).run_log(log)
            self.assertIn("/inputs/measured/columns/1", [p for p, _ in caught.exception.problems])
            self.assertIn("column 'cell/c2/force_N' is not in " + log, str(caught.exception))

    def test_dict_warning_is_a_config_warning_with_its_path(self):
        config = small_config()
        config["stages"][1]["params"]["cutoff_hz"] = 1e-300  # within bounds, not plausible
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            p = ftsense.Pipeline(config)
        self.assertEqual([w.category for w in caught], [ftsense.ConfigWarning])
        self.assertIn("/stages/1/params/cutoff_hz = 1e-300 is outside the plausible range", str(caught[0].message))
        self.assertEqual(p.warnings, [str(caught[0].message)])

    def test_not_a_config(self):
        with self.assertRaises(TypeError):
            ftsense.Pipeline(42)
        with self.assertRaises(ValueError):  # NaN is not JSON
            ftsense.Pipeline(dict(small_config(), sample_period_s=math.nan))


class PreviousTickLoop(unittest.TestCase):
    """A loop through previous_tick, r(t) = u(t) - r(t - 1) with r(-1) = 0.5: the signal is read
    by name, the monitor names it, and step and run agree."""

    def config(self):
        config = small_config()
        config["allow_dependent_virtual_sensor"] = True
        config["previous_tick"] = {"last": {"signal": "residual.residual", "dim": 3, "unit": "N", "initial": 0.5}}
        config["stages"][0]["inputs"]["virtual"] = "previous_tick.last"
        config["monitor"]["virtual"] = "previous_tick.last"
        return config

    def test_loop(self):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            p = ftsense.Pipeline(self.config())
        # The loop feeds the measured cells into the stage's and the monitor's virtual values.
        self.assertEqual([str(w.message).split(":")[0] for w in caught], ["/stages/0/inputs/virtual", "/monitor/virtual"])
        self.assertTrue(all("independence rule" in str(w.message) for w in caught))
        self.assertEqual(p.monitor["virtual"], "previous_tick.last")
        expected = [0.5, 1.5, 1.5, 2.5]  # u = 1, 2, 3, 4 on every channel
        inputs = {"measured": numpy.repeat(numpy.arange(1.0, 5.0)[:, None], 3, axis=1),
                  "reference": numpy.zeros((4, 3))}
        for k in range(4):
            tick = p.step(k * 0.001, {name: rows[k] for name, rows in inputs.items()})
            self.assertEqual(list(tick["residual.residual"]), [expected[k]] * 3)
            # After the tick: the value this tick read.
            self.assertEqual(list(p.values("previous_tick.last")), [0.5 if k == 0 else expected[k - 1]] * 3)
        whole = p.run(inputs)
        self.assertEqual(list(whole["residual.residual"][:, 1]), expected)


def re_escape(text):
    import re
    return re.escape(text)


class RobustConfig(unittest.TestCase):
    """The shipped robust pipeline: its ports as the config reference describes them."""

    def test_ports_and_columns(self):
        path = os.path.join(SOURCE, "configs", "suralp_robust.json")
        p = ftsense.Pipeline(path)
        with open(path) as f:
            config = json.load(f)
        self.assertEqual(sorted(i.name for i in p.inputs), sorted(config["inputs"]))
        for port in p.inputs:
            self.assertEqual(port.dim, len(config["inputs"][port.name]["columns"]), port.name)
        self.assertEqual(p.channels, config["monitor"]["channels"])
        self.assertEqual(p.columns[0], "time_s")
        self.assertIn("r_foot/p2/fault_type", p.columns)
        stage_names = [s["name"] for s in config["stages"]]
        for port in p.outputs:
            self.assertIn(port.name.split(".")[0], stage_names)
        # The same config as a dict (its URDF and other files resolved against configs/).
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # the shipped config has no warning
            q = ftsense.Pipeline(config, base_dir=os.path.dirname(path))
        self.assertEqual([(o.name, o.dim, o.unit) for o in q.outputs], [(o.name, o.dim, o.unit) for o in p.outputs])
        self.assertEqual(q.columns, p.columns)


if __name__ == "__main__":
    print("ftsense python API tests, seed", SEED)
    unittest.main(verbosity=2)
