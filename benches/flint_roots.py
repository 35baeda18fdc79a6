#!/usr/bin/env python3
"""python-flint's certified `complex_roots` on the peers bench's polynomials (issue 11).

Called by `cargo bench -p toolkit-benches --bench peers` when `PEERS_FLINT=1`; flint is a
reference, never a dependency of the project (`pip install python-flint`).

Input file: one query per line, `lo hi c0 c1 ... cn` (the bench writes each `f64` in Rust's
shortest round-trip form, which Python's `float` parses exactly). Each coefficient becomes
the exact rational `fmpq` of that double, so flint solves exactly the stored polynomial.

Output (stdout, two lines): the mean time per query in nanoseconds, best of `rounds` passes
over the whole corpus; then, per query, the number of distinct real roots in `(lo, hi]`. `arb_fmpz_poly_complex_roots` returns real roots with an exactly zero
imaginary part, which is what tells them from complex ones.
"""

import sys
import time

import flint


def load(path):
    queries = []
    with open(path, encoding="ascii") as f:
        for line in f:
            fields = [float(x) for x in line.split()]
            lo, hi, coeffs = fields[0], fields[1], fields[2:]
            exact = [flint.fmpq(*c.as_integer_ratio()) for c in coeffs]
            queries.append((lo, hi, flint.fmpq_poly(exact)))
    return queries


def real_roots_in(roots, lo, hi):
    return sum(1 for r, _ in roots if r.imag == 0 and lo < float(r.real.mid()) <= hi)


def main():
    path, rounds = sys.argv[1], int(sys.argv[2])
    queries = load(path)
    counts = [real_roots_in(p.complex_roots(), lo, hi) for lo, hi, p in queries]
    best = float("inf")
    for _ in range(rounds):
        start = time.perf_counter_ns()
        for _, _, p in queries:
            p.complex_roots()
        best = min(best, (time.perf_counter_ns() - start) / len(queries))
    print(best)
    print(" ".join(str(n) for n in counts))


if __name__ == "__main__":
    main()
