#!/usr/bin/python3
"""Columns for ftsense-replay-floor: for each column of an `ftsense run` output, the input column
whose numbers are about as long (mean characters per cell, every 10th row), so the floor writes
as many columns and about as many bytes. Prints them comma-separated.
Usage: replay_floor_columns.py INPUT.csv OUTPUT.csv"""
import sys


def mean_lengths(path):
    with open(path) as f:
        next(f)
        total, rows = None, 0
        for i, line in enumerate(f):
            if i % 10:
                continue
            cells = line.rstrip("\n").split(",")
            total = [len(c) for c in cells] if total is None else [t + len(c) for t, c in zip(total, cells)]
            rows += 1
    return [t / rows for t in total]


inputs, outputs = mean_lengths(sys.argv[1]), mean_lengths(sys.argv[2])
print(",".join(str(min(range(len(inputs)), key=lambda i: abs(inputs[i] - want))) for want in outputs))
