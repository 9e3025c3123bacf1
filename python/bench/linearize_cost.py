"""What calling the library from Python costs: jointlin.linearize vectorized over N
amplitudes against the Rust loop over the C entry (examples/linearize_loop.rs, the same
inputs), and a Python loop of scalar calls. Prints a Markdown table.

    python python/bench/linearize_cost.py RUST_NS_PER_CALL RUST_SUM [N]
(scripts/python-bench.sh runs both halves.)"""

import sys
import time

import numpy as np

import jointlin

MU, FN, K, OMEGA = 0.3, 2.0, 1282.7, 1.3


def best_of(runs, work):
    best = float("inf")
    for _ in range(runs):
        started = time.perf_counter()
        out = work()
        best = min(best, time.perf_counter() - started)
    return best, out


def main():
    rust_ns, rust_sum = float(sys.argv[1]), float(sys.argv[2])
    n = int(sys.argv[3]) if len(sys.argv) > 3 else 1_000_000
    slip_limit = 1.5 * MU * FN / K
    a = slip_limit * 10.0 ** (-3.0 + 4.0 * np.arange(n) / (max(n, 2) - 1))
    seconds, r = best_of(5, lambda: jointlin.linearize("mindlin", "thesis", MU, FN, K, a, OMEGA))
    r.check()
    vector_ns = seconds * 1e9 / n
    m = 10_000
    loop_seconds, _ = best_of(3, lambda: [jointlin.linearize("mindlin", "thesis", MU, FN, K, x, OMEGA) for x in a[:: n // m][:m]])
    loop_ns = loop_seconds * 1e9 / m
    agree = abs(float(r.k_star.sum()) - rust_sum) / abs(rust_sum)
    print(f"k* for A = 1e-3…10 δ* of the thesis's block (μ = 0.3, F_N = 2 N, k_T0 = 1282.7 N/mm, ω = 1.3 rad/s), best of 5:\n")
    print("| caller | ns per call | × Rust loop |")
    print("|---|---:|---:|")
    print(f"| Rust loop over `jointlin_linearize` ({n:.0e} calls) | {rust_ns:.0f} | 1.00 |")
    print(f"| `jointlin.linearize` on {n:.0e} amplitudes (NumPy) | {vector_ns:.0f} | {vector_ns / rust_ns:.2f} |")
    print(f"| Python loop of scalar `jointlin.linearize` ({m:.0e} calls) | {loop_ns:.0f} | {loop_ns / rust_ns:.1f} |")
    print(f"\nΣ k* of the two {n:.0e}-element runs agree to {agree:.1e} (relative).")


if __name__ == "__main__":
    main()
