#!/usr/bin/python3
"""Fails when a code block of a doc differs from the compiled source region it claims to show.

In the doc, a fenced block preceded by
    <!-- snippet: path/to/file.cpp#name -->
must equal the lines between `[snippet:name]` and the next `[end-snippet]` marker lines of that
file (paths from the repository root). Every ```cpp block must carry such a marker, so no C++ in
the doc escapes the compiler. A block preceded by
    <!-- json-subset-of: path/to/file.json -->
must parse as JSON and be a subset of that file: objects key by key, arrays element by element,
and the string "..." stands for any value.

usage: check_doc_snippets.py REPO_ROOT DOC.md
"""
import json
import pathlib
import re
import sys

MARKER = re.compile(r"<!--\s*(snippet|json-subset-of):\s*(\S+)\s*-->")


def region(path, name):
    lines = path.read_text().splitlines()
    start = [i for i, l in enumerate(lines) if l.strip().endswith(f"[snippet:{name}]")]
    if len(start) != 1:
        raise LookupError(f"{path}: {len(start)} start markers for snippet '{name}', expected 1")
    for j in range(start[0] + 1, len(lines)):
        if lines[j].strip().endswith("[end-snippet]"):
            return lines[start[0] + 1 : j]
    raise LookupError(f"{path}: snippet '{name}' has no [end-snippet]")


def subset(part, whole, where):
    if part == "...":
        return []
    if isinstance(part, dict):
        if not isinstance(whole, dict):
            return [f"{where}: expected an object"]
        problems = []
        for key, value in part.items():
            if key not in whole:
                problems.append(f"{where}/{key}: not in the file")
            else:
                problems += subset(value, whole[key], f"{where}/{key}")
        return problems
    if isinstance(part, list):
        if not isinstance(whole, list) or len(part) != len(whole):
            return [f"{where}: array differs in length from the file's"]
        problems = []
        for i, (p, w) in enumerate(zip(part, whole)):
            problems += subset(p, w, f"{where}/{i}")
        return problems
    return [] if part == whole else [f"{where}: {json.dumps(part)} but the file has {json.dumps(whole)}"]


def main():
    root = pathlib.Path(sys.argv[1])
    doc = pathlib.Path(sys.argv[2])
    lines = doc.read_text().splitlines()
    problems = []
    checked = 0
    pending = None
    i = 0
    while i < len(lines):
        line = lines[i]
        m = MARKER.search(line)
        if m:
            pending = (m.group(1), m.group(2), i + 1)
            i += 1
            continue
        fence = re.match(r"^```(\S*)", line)
        if not fence:
            if line.strip():
                pending = None
            i += 1
            continue
        language = fence.group(1)
        end = i + 1
        while end < len(lines) and not lines[end].startswith("```"):
            end += 1
        body = lines[i + 1 : end]
        where = f"{doc}:{i + 1}"
        try:
            if pending and pending[0] == "snippet":
                file, _, name = pending[1].partition("#")
                expected = region(root / file, name)
                if body != expected:
                    problems.append(f"{where}: differs from {file}#{name}; copy the region into the doc")
                checked += 1
            elif pending and pending[0] == "json-subset-of":
                whole = json.loads((root / pending[1]).read_text())
                problems += [f"{where}: {p}" for p in subset(json.loads("\n".join(body)), whole, "")]
                checked += 1
            elif language in ("cpp", "c++"):
                problems.append(f"{where}: a C++ block without <!-- snippet: file#name --> (not compiled)")
        except (LookupError, OSError, json.JSONDecodeError) as e:
            problems.append(f"{where}: {e}")
        pending = None
        i = end + 1
    for p in problems:
        print(p)
    if checked == 0:
        print(f"{doc}: no snippet markers found")
        return 1
    print(f"{doc}: {checked} blocks checked, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
