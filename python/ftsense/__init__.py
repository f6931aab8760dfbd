"""ftsense from Python: build a fault-tolerant sensing pipeline, step it or run it over arrays or
a CSV log, and get every signal as numpy arrays (docs/python.md).

    import ftsense, pandas
    p = ftsense.Pipeline("configs/suralp_robust.json")
    run = p.run_log("log.csv")            # the columns `ftsense run --output` writes
    df = pandas.DataFrame(run)

Every tick runs in C++ (ftsense._ftsense); long runs release the GIL. Errors are ftsense.Error
subclasses carrying ftsense's message: ConfigError (.problems: (path, message) pairs),
LogError, OutputError, UsageError.
"""

import json
import os
import tempfile
import warnings
from collections.abc import Mapping

import numpy

from . import _ftsense
from ._ftsense import ConfigError, Error, LogError, OutputError, Port, UsageError

__all__ = ["Pipeline", "Table", "FAULT_TYPES", "fault_type_name", "Report", "read_log", "calibrate", "report", "Port", "Error", "ConfigError",
           "LogError", "OutputError", "UsageError", "ConfigWarning", "LogWarning"]


# Fault type code (a run's <channel>/fault_type column) -> name, from ftsense's one table.
FAULT_TYPES = {code: name for code, name, _ in _ftsense.fault_types}


def fault_type_name(code):
    """The name of a fault type code ("none", "offset", ...); "unknown" for a code not in the table."""
    return FAULT_TYPES.get(int(code), "unknown") if code == code else "unknown"


class ConfigWarning(UserWarning):
    """A config that builds but looks wrong (a physically absurd parameter, say)."""


class LogWarning(UserWarning):
    """A log whose clock is irregular or has gaps (the pipeline was reset at each gap)."""


class Table(dict):
    """Columns by name (insertion order is the CSV's), each a 1-D numpy array: pandas.DataFrame(table).

    `summary` holds what `ftsense run` prints after a log (ticks, gap resets, first fault times)."""

    def __init__(self, names, matrix, summary=None):
        super().__init__((name, matrix[i]) for i, name in enumerate(names))
        self.summary = summary or {}

    @property
    def columns(self):
        return list(self.keys())


def _table(names, matrix, summary=None):
    return Table(list(names), matrix, summary)


class Pipeline:
    """A pipeline built from a config file path or a config dict (the JSON of docs/config_reference.md).

    thresholds: a thresholds file from `ftsense calibrate` (path) or its dict, applied first.
    base_dir: for a dict, where relative file parameters (a URDF) are resolved (default: cwd).
    A file is loaded as `ftsense run` loads it (problem paths start with the file name; warnings
    go to stderr as there); a dict's problems have bare JSON Pointer paths and its warnings are
    ConfigWarning."""

    def __init__(self, config, thresholds=None, base_dir=None):
        if isinstance(config, (str, os.PathLike)):
            if isinstance(thresholds, Mapping):
                raise TypeError("thresholds: give a file path with a config file (or load the config as a dict)")
            self._p = _ftsense.Pipeline.from_file(os.fspath(config), os.fspath(thresholds) if thresholds else "")
        elif isinstance(config, Mapping):
            if thresholds is None:
                thresholds_text = ""
            elif isinstance(thresholds, Mapping):
                thresholds_text = json.dumps(thresholds, allow_nan=False)
            else:
                with open(thresholds, encoding="utf-8") as f:
                    thresholds_text = f.read()
            self._p = _ftsense.Pipeline.from_json(json.dumps(config, allow_nan=False), thresholds_text,
                                                  os.fspath(base_dir) if base_dir else "")
            for w in self._p.warnings:
                warnings.warn(w, ConfigWarning, stacklevel=2)
        else:
            raise TypeError("config: a path to a JSON file or a dict, not " + type(config).__name__)

    # --- what the pipeline has ---
    @property
    def inputs(self):
        """The pipeline inputs: Port(name, dim, unit, columns = the log columns read)."""
        return self._p.inputs

    @property
    def outputs(self):
        """Every stage output as Port("<stage>.<port>", dim, unit, description), in run order."""
        return self._p.outputs

    @property
    def channels(self):
        """The monitored channels (empty without a monitor)."""
        return self._p.channels

    @property
    def columns(self):
        """The columns `ftsense run` writes: time_s, then per channel measured, virtual, ..."""
        return self._p.columns

    @property
    def monitor(self):
        """Monitor key ("measured", "virtual", ...) -> the signal it reads ("" for a concatenation)."""
        return dict(self._p.monitor)

    @property
    def sample_period_s(self):
        return self._p.sample_period_s

    @property
    def time_column(self):
        """The log's time column as the config declares it."""
        return self._p.time_column

    @property
    def warnings(self):
        return self._p.warnings

    # --- running ---
    def reset(self):
        """Back to the initial state (every stage reset, every buffer zeroed)."""
        self._p.reset()

    def step(self, time_s, inputs, outputs=None):
        """One tick: inputs maps every input name to its dim values; returns {signal: 1-D array}
        for `outputs` (signal names, default every stage output)."""
        return self._p.step(float(time_s), dict(inputs), outputs)

    def values(self, name):
        """The current values of a signal ("input.<name>", "<stage>.<port>" or "previous_tick.<name>")."""
        return self._p.values(name)

    def run(self, inputs, time=None, outputs=None, reset=True):
        """Every row of the inputs (name -> (ticks, dim) array; a 1-D array for a 1-value input);
        returns {signal: (ticks, dim) array} for `outputs` (default every stage output). time: one
        time per row in seconds, default k * sample_period_s. Steps each row as given: the gap and
        rate checks of run_log are the log runner's."""
        return self._p.run(dict(inputs), None if time is None else numpy.asarray(time, dtype=float), outputs, reset)

    def run_table(self, inputs, time=None, reset=True):
        """As run(), but returns the monitored channels as a Table with `ftsense run`'s columns."""
        matrix = self._p.run_table(dict(inputs), None if time is None else numpy.asarray(time, dtype=float), reset)
        return _table(self.columns, matrix)

    def run_log(self, path, gap_reset=10.0, output=None):
        """`ftsense run` over a CSV log: a Table with the columns and numbers of its CSV, and its
        summary. gap_reset: a time step longer than this many periods resets the pipeline.
        output: also write that CSV (as `ftsense run --output`). Clock problems are LogWarning."""
        matrix, clock, summary = self._p.run_log(os.fspath(path), float(gap_reset),
                                                 os.fspath(output) if output else "")
        for line in clock.splitlines():
            warnings.warn(line, LogWarning, stacklevel=2)
        return _table(self.columns, matrix, summary)

    def read_log(self, path):
        """A log's columns (Table), read as the pipeline reads it (its time column, in seconds,
        first, under its own name)."""
        names, matrix = self._p.read_log(os.fspath(path))
        return _table(names, matrix)

    def inputs_from(self, table):
        """The pipeline inputs from a table of log columns (read_log): {input: (ticks, dim) array}."""
        missing = [c for port in self.inputs for c in port.columns if c not in table]
        if missing:
            raise KeyError("columns not in the table: " + ", ".join(missing))
        return {port.name: numpy.column_stack([numpy.asarray(table[c], dtype=float) for c in port.columns])
                for port in self.inputs}

    def __repr__(self):
        return "ftsense.Pipeline(%d inputs, %d outputs, %d channels)" % (len(self.inputs), len(self.outputs),
                                                                          len(self.channels))


def read_log(path):
    """A CSV log's columns (Table) read by ftsense's reader (first column time_s)."""
    names, matrix = _ftsense.read_log(os.fspath(path))
    return _table(names, matrix)


def calibrate(config, logs, output=None, margin=None, band=False):
    """`ftsense calibrate` (the verb itself): thresholds from fault-free log(s). Writes them to
    `output` when given and returns them as a dict (pass it as Pipeline(..., thresholds=...)).
    Raises Error with the verb's message when it refuses."""
    if isinstance(logs, (str, os.PathLike)):
        logs = [logs]
    with tempfile.TemporaryDirectory() as scratch:
        target = os.fspath(output) if output else os.path.join(scratch, "thresholds.json")
        args = ["--config", os.fspath(config), "--input", ",".join(os.fspath(l) for l in logs), "--output", target]
        if margin is not None:
            args += ["--margin", repr(float(margin))]
        if band:
            args.append("--band")
        status, out, err = _ftsense.calibrate(args)
        if status != 0:
            raise Error((err or out).strip())
        for line in err.splitlines():
            warnings.warn(line, LogWarning, stacklevel=2)
        with open(target, encoding="utf-8") as f:
            return json.load(f)


class Report:
    """What `ftsense report` computes: `metrics` (the dict of metrics.json) and `table` (its text)."""

    def __init__(self, metrics, table):
        self.metrics = metrics
        self.table = table

    def __repr__(self):
        return self.table


def report(run, truth=None, out=None, warmup_s=2.0, figures=True, title="ftsense run"):
    """`ftsense report`'s metrics of a run (the CSV of `ftsense run` or Pipeline.run_log(output=...))
    against the truth log; with `out`, also metrics.json, report.md and the figures there."""
    metrics, table = _ftsense.report(os.fspath(run), os.fspath(truth) if truth else "", os.fspath(out) if out else "",
                                     float(warmup_s), bool(figures), title)
    return Report(json.loads(metrics), table)
