# Copyright (c) 2026 The Isophotic_metric developers.
# This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
# SPDX-License-Identifier: GPL-3.0-or-later
"""Overhead of the Python module: the same calls on the same mesh from Python and from C++.

    python3 bench_overhead.py <bench_overhead binary> [mesh] [repetitions] [rounds]

Runs the C++ program (Google Benchmark, bench_overhead.cpp) and the Python calls alternately, so
that both see the same load, and prints the medians and their ratio for every call, of the wall-clock
time and of the process's CPU time (the calls are serial; CPU time is less disturbed by other
processes on a loaded machine).
"""
import json
import os
import statistics
import subprocess
import sys
import time

import isophotic_metric as im


def python_times(mesh, repetitions):
    L = im.suggested_weight_length_scale(mesh)
    calls = {
        "Distances/euclidean": lambda: im.compute_geodesic_distances(
            mesh, [0], euclidean_weight=1.0, isophotic_weight=0.0, weight_length_scale=L),
        "Distances/isophotic": lambda: im.compute_geodesic_distances(
            mesh, [0], euclidean_weight=0.5, isophotic_weight=0.5, weight_length_scale=L),
        "Dilation": lambda: im.dilate_face_selection(
            mesh, [0], 0.1 * L, euclidean_weight=0.5, isophotic_weight=0.5, weight_length_scale=L),
    }
    times = {}
    for name, call in calls.items():
        call()  # warm-up, as Google Benchmark's first runs
        samples = []
        for _ in range(repetitions):
            wall, cpu = time.perf_counter(), time.process_time()
            call()
            samples.append((time.perf_counter() - wall, time.process_time() - cpu))
        times[name] = samples
    return times


def cpp_times(program, path, repetitions):
    out = subprocess.run([program, path, "--benchmark_format=json", f"--benchmark_repetitions={repetitions}",
                          "--benchmark_min_time=0.01"], check=True, capture_output=True, text=True).stdout
    times = {}
    for b in json.loads(out)["benchmarks"]:
        if b.get("run_type") == "iteration":
            times.setdefault(b["run_name"], []).append((b["real_time"] / 1e3, b["cpu_time"] / 1e3))  # ms -> s
    return times


def main():
    program = sys.argv[1]
    data = os.environ.get("CGAL_DATA_DIR", os.path.join(os.path.dirname(__file__), "../../build/cgal_data/data"))
    path = sys.argv[2] if len(sys.argv) > 2 else os.path.join(data, "meshes", "elephant.off")
    repetitions = int(sys.argv[3]) if len(sys.argv) > 3 else 5
    rounds = int(sys.argv[4]) if len(sys.argv) > 4 else 3
    mesh = im.Mesh(path)
    print(f"{os.path.basename(path)}: {mesh.number_of_faces} faces; load {os.getloadavg()[0]:.2f}")
    py, cpp = {}, {}
    for _ in range(rounds):  # alternate: C++, Python, C++, Python, ...
        for name, samples in cpp_times(program, path, repetitions).items():
            cpp.setdefault(name, []).extend(samples)
        for name, samples in python_times(mesh, repetitions).items():
            py.setdefault(name, []).extend(samples)
    print(f"{'call':22s} {'wall C++':>10s} {'Python':>10s} {'ratio':>6s}   {'CPU C++':>10s} {'Python':>10s} {'ratio':>6s}")
    for name in py:
        row = f"{name:22s}"
        for k in (0, 1):
            c = statistics.median(s[k] for s in cpp[name])
            p = statistics.median(s[k] for s in py[name])
            row += f" {c * 1e3:7.1f} ms {p * 1e3:7.1f} ms {p / c:6.3f}  "
        print(row)
    print(f"load after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
