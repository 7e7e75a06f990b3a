#!/usr/bin/env python3
"""Stress study for STABILITY.md: run after `cargo build --release`.

Usage: python3 benches/extremes.py > /tmp/stability-tables.md
Each section prints a Markdown table and the commands behind it.
"""
import json
import os
import re
import subprocess
import tempfile
import time

BIN = os.path.join(os.path.dirname(__file__), "..", "target", "release", "riplab")
ROOT = os.path.join(os.path.dirname(__file__), "..")
PAPER = open(os.path.join(ROOT, "scenarios", "hertz-paper.toml")).read()


def run(*args):
    t = time.perf_counter()
    p = subprocess.run([BIN, *args], capture_output=True, text=True)
    return p, (time.perf_counter() - t) * 1e3


def solve_json(*args):
    p, ms = run("solve", *args, "--format", "json")
    if p.returncode not in (0, 1):
        return None, p.stderr.strip(), ms
    out = json.loads(p.stdout)
    return (out if isinstance(out, list) else [out]), p.stderr.strip(), ms


def scenario(**edits):
    text = PAPER
    for key, line in edits.items():
        text = re.sub(rf"(?m)^{key} = .*$", line, text, count=1)
    f = tempfile.NamedTemporaryFile("w", suffix=".toml", delete=False)
    f.write(text)
    f.close()
    return f.name


def epsilon_decades():
    kappas = [10.0 ** -k for k in range(2, 15)]
    print("## ε over twelve decades (scaled: ε = κ·h/E)\n")
    print("`riplab solve --scheme S --level L --kappa 1e-2,1e-3,…,1e-14` and `--epsilon 0` (exact).")
    print("Each cell: Newton iterations / relative load error against the exact-constraint load.\n")
    print("| scheme | level | " + " | ".join(f"κ=1e-{k}" for k in range(2, 15)) + " |")
    print("|---|---|" + "---|" * len(kappas))
    for scheme in ["M1", "M3"]:
        for level in range(0, 7):
            exact, _, _ = solve_json("--scheme", scheme, "--level", str(level), "--epsilon", "0")
            p0 = exact[0]["load"]
            rows, _, _ = solve_json("--scheme", scheme, "--level", str(level), "--kappa", ",".join(f"{k:g}" for k in kappas))
            cells = []
            for r in rows:
                flag = "" if r["converged"] else " ✗"
                cells.append(f"{r['newton_iterations']}/{abs(r['load'] - p0) / p0:.0e}{flag}")
            print(f"| {scheme} | {level} | " + " | ".join(cells) + " |")
    print()


def incompressible():
    print("## Near-incompressible material (M3, exact constraint, level 3)\n")
    print("| ν | Q1 full | Q1 selective | Q2 selective (level 4, reference) | Q1 full / reference |")
    print("|---|---|---|---|---|")
    for nu in ["0.45", "0.49", "0.499", "0.4999"]:
        loads = []
        for el, integ, level in [("q1", "full", 3), ("q1", "selective", 3), ("q2", "selective", 4)]:
            f = scenario(poisson=f"poisson = {nu}", element=f'element = "{el}"', level=f'level = {level}\nintegration = "{integ}"')
            rule = "simpson" if el == "q2" else "trapezoid"
            rows, _, _ = solve_json(f, "--rule", rule, "--epsilon", "0")
            loads.append(rows[0]["load"])
            os.unlink(f)
        print(f"| {nu} | {loads[0]:.2f} | {loads[1]:.2f} | {loads[2]:.2f} | {loads[0] / loads[2]:.3f} |")
    print()


def geometry():
    print("## Geometric extremes (M1, level 2 unless said)\n")
    print("| case | command | result | ms |")
    print("|---|---|---|---|")
    cases = [
        ("no contact (obstacle 0.1 above)", ["--level", "2", "--depth=-0.1"], {}),
        ("depth 3.5 of height 4", ["--level", "2", "--depth", "3.5"], {}),
        ("obstacle much wider than the body (R = 1000)", ["--level", "2"], {"radius": "radius = 1000.0", "depth": "depth = 0.1"}),
        ("contact zone of one point (level 0, depth 0.02)", ["--level", "0", "--depth", "0.02"], {}),
        ("level-0 mesh one element high", ["--level", "2"], {"ny": "ny = 1"}),
    ]
    for name, args, edits in cases:
        f = scenario(**edits) if edits else None
        rows, err, ms = solve_json(*([f] if f else []), *args)
        r = rows[0]
        touching = sum(1 for p in r["points"]["p"] if p > 0)
        res = f"{'converged' if r['converged'] else 'NOT converged'} in {r['newton_iterations']} iterations; load {r['load']:.4g}; {touching}/{len(r['points']['p'])} points in contact"
        cmd = "riplab solve " + (f"<scenario with {', '.join(edits.values())}> " if edits else "") + " ".join(args)
        print(f"| {name} | `{cmd}` | {res} | {ms:.0f} |")
        if f:
            os.unlink(f)
    p, ms = run("solve", "--element", "q2", "--level", "8")
    print(f"| size beyond the machine | `riplab solve --element q2 --level 8` | exit {p.returncode}: {p.stderr.strip()} | {ms:.0f} |")
    print()


def determinism():
    print("## Determinism\n")
    outs = []
    for _ in range(2):
        rows, _, _ = solve_json("--level", "5")
        r = rows[0]
        r.pop("timing_ms")
        outs.append(json.dumps(r, sort_keys=True))
    print(f"Two runs of `riplab solve --level 5 --format json` (timings removed): {'bit-identical' if outs[0] == outs[1] else 'DIFFERENT'}.")
    print("faer runs sequentially (Par::Seq) throughout, so the thread count cannot change the result.\n")


def bad_input():
    print("## Bad input (tests/bad/, run by `cargo test --test cli bad_input::`)\n")
    print("| file | exit | message (first line) |")
    print("|---|---|---|")
    bad = os.path.join(ROOT, "tests", "bad")
    for name in sorted(os.listdir(bad)):
        p, _ = run("solve", os.path.join(bad, name))
        first = p.stderr.strip().splitlines()[0].replace(os.path.abspath(bad) + "/", "").replace("|", "\\|")
        print(f"| {name} | {p.returncode} | {first} |")
    print()


if __name__ == "__main__":
    epsilon_decades()
    incompressible()
    geometry()
    determinism()
    bad_input()
