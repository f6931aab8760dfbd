#!/usr/bin/python3
"""docs/ftsense-config.schema.json against the configs ftsense reads.

check_config_schema.py FTSENSE ROOT
  1. the schema is a valid draft-07 schema;
  2. every pipeline config shipped under configs/, examples/ and tests/cli (every JSON file with
     a "stages" key) validates against it, and `ftsense check` accepts it (a config for a user's
     program is checked with that program's plugins added to the plugin names);
  3. one good config broken in one place at a time (unknown plugin, wrong parameter type, ...)
     is rejected by the schema, at the place broken, and by `ftsense check` (exit 2).
Needs python3-jsonschema (Debian; `make deps` installs it).
"""
import copy
import json
import pathlib
import subprocess
import sys
import tempfile

try:
    import jsonschema
except ImportError:
    sys.exit("check_config_schema.py needs python3-jsonschema: run `make deps` "
             "(or apt-get install python3-jsonschema)")

ftsense, root = sys.argv[1], pathlib.Path(sys.argv[2])
schema = json.loads((root / "docs/ftsense-config.schema.json").read_text())
failures = []


def fail(message):
    failures.append(message)
    print("FAIL:", message)


# 1. A draft-07 schema.
if schema.get("$schema") != "http://json-schema.org/draft-07/schema#":
    fail("the schema does not declare draft-07")
jsonschema.Draft7Validator.check_schema(schema)
validator = jsonschema.Draft7Validator(schema)


def ftsense_check(path):
    return subprocess.run([ftsense, "check", "--config", str(path)], capture_output=True, text=True)


# 2. Every shipped pipeline config is valid.
shipped = []
for folder in ("configs", "examples", "tests/cli"):
    for path in sorted((root / folder).rglob("*.json")):
        text = path.read_text()
        try:
            config = json.loads(text)
        except json.JSONDecodeError:
            continue
        if isinstance(config, dict) and "stages" in config:
            shipped.append((path, config))
if len(shipped) < 6:
    fail(f"found only {len(shipped)} pipeline configs under configs/, examples/ and tests/cli")
known_plugins = schema["definitions"]["stage"]["properties"]["plugin"]["enum"]
foreign = 0
for path, config in shipped:
    name = path.relative_to(root)
    # A config for a user's program (examples/insole_fdi) names plugins ftsense lacks: ftsense's
    # schema rejects exactly those names, as `ftsense check` does, and passes the rest; the
    # user's program prints its own schema.
    own = sorted({s.get("plugin") for s in config["stages"]} - set(known_plugins))
    if own:
        foreign += 1
        errors = list(validator.iter_errors(config))
        wrong = [e for e in errors if not (len(e.absolute_path) == 3 and e.absolute_path[0] == "stages"
                                           and e.absolute_path[2] == "plugin" and e.instance in own)]
        for e in wrong:
            fail(f"{name}: /{'/'.join(map(str, e.absolute_path))}: {e.message}")
        if not errors:
            fail(f"{name}: the schema accepts plugins ftsense lacks: {own}")
        extended = copy.deepcopy(schema)
        extended["definitions"]["stage"]["properties"]["plugin"]["enum"] += own
        errors = list(jsonschema.Draft7Validator(extended).iter_errors(config))
    else:
        errors = list(validator.iter_errors(config))
        result = ftsense_check(path)
        if result.returncode != 0:
            fail(f"{name}: ftsense check exits {result.returncode}: {result.stderr.strip()}")
    for e in errors:
        fail(f"{name}: /{'/'.join(map(str, e.absolute_path))}: {e.message}")
print(f"{len(shipped)} shipped configs validate ({foreign} with plugins of their own program)")

# 3. Broken configs are rejected by both. Each mutation names the JSON path it breaks.
base_path = root / "configs/suralp.json"
base = json.loads(base_path.read_text())
stage_of = {s["plugin"]: i for i, s in reversed(list(enumerate(base["stages"])))}
low_pass = stage_of["low_pass"]
threshold = stage_of["threshold_detector"]
recovery = stage_of["fault_recovery"]


def mutated(change):
    config = copy.deepcopy(base)
    change(config)
    return config


def set_in(path, value):
    def change(config):
        node = config
        for key in path[:-1]:
            node = node[key]
        node[path[-1]] = value
    return change


bad = [
    ("unknown plugin kind", ["stages", low_pass, "plugin"], set_in(["stages", low_pass, "plugin"], "low_passs")),
    ("parameter of the wrong type", ["stages", low_pass, "params", "cutoff_hz"],
     set_in(["stages", low_pass, "params", "cutoff_hz"], "1 Hz")),
    ("unknown parameter", ["stages", low_pass, "params"], set_in(["stages", low_pass, "params", "cutoff"], 1.0)),
    ("parameter out of bounds", ["stages", low_pass, "params", "cutoff_hz"],
     set_in(["stages", low_pass, "params", "cutoff_hz"], 0.0)),
    ("list of the wrong element type", ["stages", threshold, "params", "thresholds", 0],
     set_in(["stages", threshold, "params", "thresholds"], ["100"])),
    ("unknown choice", ["stages", recovery, "params", "correction"],
     set_in(["stages", recovery, "params", "correction"], "sometimes")),
    ("unknown input port of the plugin", ["stages", low_pass, "inputs"],
     lambda c: c["stages"][low_pass]["inputs"].update({"signals": c["stages"][low_pass]["inputs"]["signal"]})),
    ("wire not of the form node.port", ["stages", low_pass, "inputs", "signal"],
     set_in(["stages", low_pass, "inputs", "signal"], "fdi-fault_estimate")),
    ("wire selection not [i] or [i:j]", ["stages", low_pass, "inputs", "signal"],
     set_in(["stages", low_pass, "inputs", "signal"], "fdi.fault_estimate[1;2]")),
    ("unknown top-level key", [], set_in(["sample_period"], 0.001)),
    ("sample period of the wrong type", ["sample_period_s"], set_in(["sample_period_s"], "1 ms")),
    ("unknown time unit", ["time", "unit"], set_in(["time"], {"column": "time_s", "unit": "min"})),
    ("input scale of the wrong type", ["inputs", next(iter(base["inputs"])), "scale"],
     set_in(["inputs", next(iter(base["inputs"])), "scale"], "2")),
    ("missing required key", [], lambda c: c.pop("stages")),
]
with tempfile.TemporaryDirectory() as tmp:
    for what, where, change in bad:
        config = mutated(change)
        errors = list(validator.iter_errors(config))
        if not errors:
            fail(f"the schema accepts a config with {what}")
        elif not any(list(e.absolute_path)[:len(where)] == where for e in errors):
            fail(f"{what}: the schema reports {[list(e.absolute_path) for e in errors]}, not at {where}")
        # ftsense resolves relative paths from the config's folder: write it beside the original.
        path = pathlib.Path(tmp) / "bad.json"
        path.write_text(json.dumps(config))
        result = ftsense_check(path)
        pointer = "bad.json:/" + "/".join(map(str, where))
        if result.returncode != 2 or pointer not in result.stderr:
            fail(f"ftsense check on a config with {what}: exit {result.returncode} (not 2) or no error at "
                 f"{pointer}: {result.stderr.strip()}")
print(f"{len(bad)} broken configs tried")

if failures:
    sys.exit(f"{len(failures)} failures")
print("config schema: all checks passed")
