#!/usr/bin/python3
"""Runs a pipeline over a log with the ftsense Python module and plots, per channel, the measured,
virtual and recovered signals, the true one when the log has it (simulator logs), and the time
the channel is flagged, with the fault type named.

    PYTHONPATH=build/python python3 python/examples/plot_run.py configs/suralp_robust.json log.csv \
        --out run.png [--channel r_foot/p2 ...]

Without --channel it draws the flagged channels (the first four when none is). Needs
python3-matplotlib."""

import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")  # files only, no display needed
import matplotlib.pyplot as plt
import numpy

import ftsense


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("config", help="pipeline config (JSON)")
    parser.add_argument("log", help="input log (CSV)")
    parser.add_argument("-o", "--out", default="run.png", help="figure to write (PNG, PDF, SVG)")
    parser.add_argument("-c", "--channel", action="append", help="channel to draw (repeat for several)")
    args = parser.parse_args()

    pipeline = ftsense.Pipeline(args.config)
    run = pipeline.run_log(args.log)
    log = pipeline.read_log(args.log)
    t = run["time_s"]
    unit = next(c for c in run if c.endswith("/measured_" + c.rsplit("_", 1)[-1])).rsplit("_", 1)[-1]
    channels = args.channel or [c for c in pipeline.channels if run[c + "/fault"].any()] or pipeline.channels[:4]
    unknown = [c for c in channels if c not in pipeline.channels]
    if unknown:
        sys.exit("plot_run.py: no channel %s; the config monitors %s" % (", ".join(unknown), ", ".join(pipeline.channels)))

    fig, axes = plt.subplots(len(channels), 1, sharex=True, figsize=(10, 2.4 * len(channels) + 0.8), squeeze=False)
    for ax, ch in zip(axes[:, 0], channels):
        flagged = run[ch + "/fault"] != 0
        if flagged.any():
            ax.fill_between(t, 0, 1, where=flagged, transform=ax.get_xaxis_transform(), color="tab:red", alpha=0.15,
                            step="post", label="flagged")
            first = int(numpy.argmax(flagged))
            kind = ftsense.fault_type_name(run[ch + "/fault_type"][first])
            ax.axvline(t[first], color="tab:red", lw=0.8)
            ax.annotate("flagged at %.3f s: %s" % (t[first], kind), (t[first], 0.95), xycoords=("data", "axes fraction"), va="top",
                        xytext=(4, 0), textcoords="offset points", color="tab:red", fontsize=8)
        ax.plot(t, run["%s/measured_%s" % (ch, unit)], color="0.55", lw=0.8, label="measured")
        ax.plot(t, run["%s/virtual_%s" % (ch, unit)], color="tab:blue", lw=1.0, label="virtual")
        ax.plot(t, run["%s/recovered_%s" % (ch, unit)], color="tab:green", lw=1.0, label="recovered")
        truth = "truth/%s/force_%s" % (ch, unit)
        if truth in log:
            ax.plot(log["time_s"], log[truth], color="black", lw=1.0, ls="--", label="true")  # dashed, on top
        ax.set_ylabel("%s [%s]" % (ch, unit))
        ax.grid(alpha=0.3)
    # One legend for every panel, under the title (a panel's own would hide its curves).
    legend = {}
    for ax in axes[:, 0]:
        for handle, label in zip(*ax.get_legend_handles_labels()):
            legend.setdefault(label, handle)
    height = fig.get_figheight()
    fig.suptitle("%s on %s" % (os.path.basename(args.config), os.path.basename(args.log)), y=1 - 0.1 / height)
    fig.legend(legend.values(), legend.keys(), loc="upper center", ncol=len(legend), fontsize=8,
               bbox_to_anchor=(0.5, 1 - 0.32 / height), frameon=False)
    axes[-1, 0].set_xlabel("time [s]")
    fig.tight_layout(rect=(0, 0, 1, 1 - 0.6 / height))
    fig.savefig(args.out, dpi=110)
    print("wrote", args.out, "(channels: %s)" % ", ".join(channels))


if __name__ == "__main__":
    main()
