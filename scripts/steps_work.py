#!/usr/bin/env python3
"""Summarises a CONTACT_STEPS_WORK file of examples/contact_steps (issue 35's 20x rule).

    CONTACT_STEPS_WORK=wall.txt target/release/examples/contact_steps wall 400
    python3 scripts/steps_work.py wall.txt [RATIO]

Prints the median work per step (row updates, deterministic), the worst step after the
first and its ratio to the median, the steps over 20x the median, the total work and the
unconverged steps; then each step over RATIO times the median (default 20) with the solver
paths it took (the counters' changes in that step: direct, declined, warm, nsweeps,
nsub, fwarm, fdirect, fsweeps, fsub, interior, isteps), when the file has them.
"""
import sys

COLUMNS = ("step work rows residual budget interior isteps fsweeps fsub "
           "direct declined warm nsweeps nsub fwarm fdirect").split()


def main():
    path = sys.argv[1]
    ratio = float(sys.argv[2]) if len(sys.argv) > 2 else 20.0
    lines = [line.split() for line in open(path) if line.strip()]
    work = [int(v[1]) for v in lines]
    median = sorted(work)[len(work) // 2]
    worst = max(range(1, len(work)), key=lambda i: work[i]) if len(work) > 1 else 0
    over = sum(1 for w in work[1:] if w > 20 * max(median, 1))
    unconverged = sum(1 for v in lines if float(v[3]) != 0.0)
    print(f"steps {len(work)}  median {median}  worst after step 1 {work[worst]} "
          f"(step {worst + 1}, x{work[worst] / max(median, 1):.1f})  steps over 20x {over}  "
          f"total {sum(work)}  unconverged {unconverged}")
    previous = None
    for v in lines:
        row = dict(zip(COLUMNS, v))
        counters = {k: int(row[k]) for k in COLUMNS[5:] if k in row}
        if int(row["work"]) > ratio * max(median, 1):
            changes = {k: c - (previous or {}).get(k, 0) for k, c in counters.items()}
            paths = " ".join(f"{k}={c}" for k, c in changes.items() if c)
            print(f"  step {row['step']}: work {row['work']} rows {row['rows']} "
                  f"residual {row['residual']}  {paths}")
        previous = counters


if __name__ == "__main__":
    main()
