#!/usr/bin/python3
"""Plots of the flexible-joint seed's examples from the CSV files of tfmb-beam-flexible-joint-seed.

    plot_seed_examples.py <folder with example1.csv, example2*.csv> [-o <folder for the PNGs>]

example1.png: stretch and wryness components vs the load factor a for the typical and the proposed
measures, handles in the seed's order (solid) and swapped (dashed, sign-flipped: swapping inverts
the relative motion); the seed's Figs. 3-6. example2*.png: the sixteen lambda/mu cases, one row per
table row, the seed's Figs. 7-14.
"""
import argparse
import csv
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

COLOURS = ["tab:blue", "tab:orange", "tab:green"]


def read(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def example1(rows, out):
    fig, axes = plt.subplots(2, 2, figsize=(11, 8), sharex=True)
    for col, measure in enumerate(["typical", "proposed"]):
        for row, (kind, label) in enumerate([("stretch", "stretch e"), ("wryness", "wryness kappa")]):
            ax = axes[row, col]
            for order, style in [("kl", "-"), ("lk", "--")]:
                sel = [r for r in rows if r["measure"] == measure and r["handles"] == order]
                a = [float(r["a"]) for r in sel]
                sign = -1.0 if order == "lk" else 1.0
                for i in range(3):
                    ax.plot([0] + a, [0] + [sign * float(r[f"{kind}_{i + 1}"]) for r in sel], style, color=COLOURS[i],
                            label=f"{kind[0]}{i + 1}, {'k/l as the seed' if order == 'kl' else 'k/l swapped (sign flipped)'}")
            ax.set_title(f"{measure} measures: {label}")
            ax.grid(True, alpha=0.3)
            if row == 1:
                ax.set_xlabel("load factor a")
    axes[0, 0].legend(fontsize=7)
    fig.suptitle("flexible-joint seed, example 1: swapping handles k and l")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def example2(rows, out, title):
    fig, axes = plt.subplots(4, 2, figsize=(11, 14), sharex=True)
    styles = {"a": "-", "b": "--", "c": "-.", "d": ":"}
    for r_index, table_row in enumerate("1234"):
        for col, kind in enumerate(["stretch", "wryness"]):
            ax = axes[r_index, col]
            for letter in "abcd":
                case = table_row + letter
                sel = [r for r in rows if r["case"] == case]
                if not sel:
                    continue
                a = [0.0] + [float(r["a"]) for r in sel]
                for i in range(3):
                    ax.plot(a, [0.0] + [float(r[f"{kind}_{i + 1}"]) for r in sel], styles[letter], color=COLOURS[i],
                            label=f"{case}: lambda = {sel[0]['lambda']}, mu = {sel[0]['mu']}" if i == 0 else None)
            ax.set_title(f"cases {table_row}a-{table_row}d: {kind} (blue 1, orange 2, green 3)", fontsize=9)
            ax.grid(True, alpha=0.3)
            if col == 0:
                ax.legend(fontsize=7)
    for ax in axes[-1]:
        ax.set_xlabel("load factor a")
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(out, dpi=100)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("folder")
    p.add_argument("-o", "--output", default=None)
    args = p.parse_args()
    out = args.output or args.folder
    os.makedirs(out, exist_ok=True)
    example1(read(os.path.join(args.folder, "example1.csv")), os.path.join(out, "example1.png"))
    example2(read(os.path.join(args.folder, "example2.csv")), os.path.join(out, "example2.png"),
             "flexible-joint seed, example 2: sixteen lambda/mu cases (rotational stiffness 1000, 1000, 100 as printed)")
    example2(read(os.path.join(args.folder, "example2-rot1000.csv")), os.path.join(out, "example2-rot1000.png"),
             "flexible-joint seed, example 2: sixteen lambda/mu cases (rotational stiffness 1000 about every axis)")


if __name__ == "__main__":
    main()
