#!/usr/bin/env python3
"""Independent reference for the Duffing oscillator of the thesis's Appendix B:

    x'' + x' + 20 x + 40 x^3 = 30 sin(10 t),  x(0) = 0.2, x'(0) = 0      (B.1)

integrated with an adaptive Dormand-Prince 5(4) pair (not the classical RK4 of the
project's own integrator, no code shared with it), relative and absolute tolerance
1e-12, to t = 60 (the transient decays like exp(-t/2)); prints the steady maximum of x
over the last three forcing periods, located within each step by cubic Hermite
interpolation (error ~h^4, below 1e-11 at these steps). Used as INDEPENDENT_DUFFING_RK in examples/seed_cases/cases.rs and checked
by tests/seed_cases.rs. Standard library only.
"""
import math

D, K, ALPHA, F, OMEGA = 1.0, 20.0, 40.0, 30.0, 10.0


def rhs(t, y):
    x, v = y
    return (v, F * math.sin(OMEGA * t) - D * v - K * x - ALPHA * x ** 3)


# Dormand-Prince 5(4) tableau.
C = (0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0, 1.0)
A = (
    (),
    (1 / 5,),
    (3 / 40, 9 / 40),
    (44 / 45, -56 / 15, 32 / 9),
    (19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729),
    (9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656),
    (35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84),
)
B5 = (35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84, 0.0)
B4 = (5179 / 57600, 0.0, 7571 / 16695, 393 / 640, -92097 / 339200, 187 / 2100, 1 / 40)


def step(t, y, h):
    k = []
    for i in range(7):
        yi = [y[j] + h * sum(A[i][m] * k[m][j] for m in range(i)) for j in range(2)]
        k.append(rhs(t + C[i] * h, yi))
    y5 = [y[j] + h * sum(B5[i] * k[i][j] for i in range(7)) for j in range(2)]
    y4 = [y[j] + h * sum(B4[i] * k[i][j] for i in range(7)) for j in range(2)]
    return y5, y4, k


def hermite(t0, y0, f0, t1, y1, f1, t):
    """Cubic Hermite interpolation of x between two accepted steps."""
    h = t1 - t0
    s = (t - t0) / h
    h00, h10 = 2 * s ** 3 - 3 * s ** 2 + 1, s ** 3 - 2 * s ** 2 + s
    h01, h11 = -2 * s ** 3 + 3 * s ** 2, s ** 3 - s ** 2
    return h00 * y0 + h10 * h * f0 + h01 * y1 + h11 * h * f1


def main():
    tol, t_end = 1e-12, 60.0
    period = 2 * math.pi / OMEGA
    window = t_end - 3 * period
    t, y, h = 0.0, [0.2, 0.0], 1e-4
    best = -math.inf
    while t < t_end:
        h = min(h, t_end - t)
        y5, y4, _ = step(t, y, h)
        err = max(abs(y5[j] - y4[j]) / (tol + tol * max(abs(y[j]), abs(y5[j]))) for j in range(2))
        if err <= 1.0:
            if t + h > window:
                # Maximum of x on this step: x' = v changes sign from + to -.
                f0, f1 = y[1], y5[1]
                samples = [hermite(t, y[0], f0, t + h, y5[0], f1, t + h * i / 64) for i in range(65)]
                best = max(best, max(samples))
            t, y = t + h, y5
        h *= min(5.0, max(0.2, 0.9 * (1.0 / max(err, 1e-300)) ** 0.2))
    print(f"{best:.6f}")


if __name__ == "__main__":
    main()
